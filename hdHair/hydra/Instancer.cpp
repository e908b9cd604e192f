#include "hdHair/hydra/Instancer.h"

#include <cmath>
#include <iterator>
#include <set>

#include "pxr/base/gf/matrix4f.h"
#include "pxr/base/gf/quatd.h"
#include "pxr/base/gf/quatf.h"
#include "pxr/base/gf/quath.h"
#include "pxr/base/gf/rotation.h"
#include "pxr/base/gf/vec4f.h"
#include "pxr/base/tf/diagnostic.h"
#include "pxr/base/vt/array.h"
#include "pxr/imaging/hd/changeTracker.h"
#include "pxr/imaging/hd/renderIndex.h"
#include "pxr/imaging/hd/sceneDelegate.h"
#include "pxr/imaging/hd/tokens.h"

#include "hdHair/hydra/VtValueConversion.h"

PXR_NAMESPACE_OPEN_SCOPE

namespace {

bool isTransformPrimvar(TfToken const& name) {
    return name == HdInstancerTokens->instanceTranslations || name == HdInstancerTokens->instanceRotations ||
           name == HdInstancerTokens->instanceScales || name == HdInstancerTokens->instanceTransforms;
}

// Rotations arrive as half, float or double quaternions (PointInstancer
// orientations are quath), or as GfVec4f (real, i, j, k) from older
// delegates. Read through GetReal/GetImaginary, never by memory layout.
template <typename Quat>
bool appendQuaternions(VtValue const& value, std::vector<GfQuatd>* out) {
    if (!value.IsHolding<VtArray<Quat>>()) return false;
    for (Quat const& q : value.UncheckedGet<VtArray<Quat>>())
        out->emplace_back(double(q.GetReal()), GfVec3d(q.GetImaginary()));
    return true;
}

bool toQuaternions(VtValue const& value, std::vector<GfQuatd>* out) {
    if (appendQuaternions<GfQuath>(value, out) || appendQuaternions<GfQuatf>(value, out) ||
        appendQuaternions<GfQuatd>(value, out))
        return true;
    if (value.IsHolding<VtVec4fArray>()) {
        for (GfVec4f const& q : value.UncheckedGet<VtVec4fArray>()) out->emplace_back(q[0], GfVec3d(q[1], q[2], q[3]));
        return true;
    }
    return false;
}

bool toMatrices(VtValue const& value, std::vector<GfMatrix4d>* out) {
    if (value.IsHolding<VtMatrix4dArray>()) {
        VtMatrix4dArray const& matrices = value.UncheckedGet<VtMatrix4dArray>();
        out->assign(matrices.begin(), matrices.end());
        return true;
    }
    if (value.IsHolding<VtMatrix4fArray>()) {
        for (GfMatrix4f const& m : value.UncheckedGet<VtMatrix4fArray>()) out->emplace_back(m);
        return true;
    }
    return false;
}

}  // namespace

HdHairInstancer::HdHairInstancer(HdSceneDelegate* delegate, SdfPath const& id) : HdInstancer(delegate, id) {}

void HdHairInstancer::Sync(HdSceneDelegate* sceneDelegate, HdRenderParam*, HdDirtyBits* dirtyBits) {
    _UpdateInstancer(sceneDelegate, dirtyBits);
    SdfPath const& id = GetId();
    if (!HdChangeTracker::IsAnyPrimvarDirty(*dirtyBits, id)) return;
    // Instance-rate primvars other than transforms (per-instance colours)
    // are not read: hdHair's strands take their primvars from the prototype.
    std::set<TfToken> present;
    for (HdPrimvarDescriptor const& descriptor :
         sceneDelegate->GetPrimvarDescriptors(id, HdInterpolationInstance)) {
        if (!isTransformPrimvar(descriptor.name)) continue;
        present.insert(descriptor.name);
        if (HdChangeTracker::IsPrimvarDirty(*dirtyBits, id, descriptor.name))
            _transformPrimvars[descriptor.name] = sceneDelegate->Get(id, descriptor.name);
    }
    // A transform primvar no longer authored (scales removed, say) stops applying.
    for (auto it = _transformPrimvars.begin(); it != _transformPrimvars.end();)
        it = present.count(it->first) ? std::next(it) : _transformPrimvars.erase(it);
}

std::vector<GfMatrix4d> HdHairInstancer::_ComputeLocalTransforms(SdfPath const& prototypeId) const {
    SdfPath const& id = GetId();
    HdSceneDelegate* delegate = GetDelegate();
    GfMatrix4d const instancerTransform = delegate->GetInstancerTransform(id);
    VtIntArray const indices = delegate->GetInstanceIndices(id, prototypeId);

    // Gf matrices act on row vectors: A * B applies A first. The instance's
    // own matrix goes first, then scale, rotation, translation, and the
    // instancer's transform last (UsdGeomPointInstancer's order).
    std::vector<GfMatrix4d> transforms(indices.size(), GfMatrix4d(1.0));
    auto forEachInstance = [&](TfToken const& name, size_t count, auto&& compose) {
        if (!_transformPrimvars.count(name)) return;
        size_t missing = 0;
        for (size_t i = 0; i < indices.size(); ++i) {
            int index = indices[i];
            if (index < 0 || size_t(index) >= count) {
                ++missing;
                continue;
            }
            compose(i, size_t(index));
        }
        if (missing)
            TF_WARN("hdHair: %s.%s: %zu instances have no value (%zu given); they use the identity there",
                    id.GetText(), name.GetText(), missing, count);
    };
    auto lookup = [&](TfToken const& name) {
        auto found = _transformPrimvars.find(name);
        return found == _transformPrimvars.end() ? VtValue() : found->second;
    };

    std::vector<GfMatrix4d> matrices;
    VtValue value = lookup(HdInstancerTokens->instanceTransforms);
    if (!value.IsEmpty() && !toMatrices(value, &matrices))
        TF_WARN("hdHair: %s.%s: expected matrices, got %s; ignored", id.GetText(),
                HdInstancerTokens->instanceTransforms.GetText(), value.GetTypeName().c_str());
    forEachInstance(HdInstancerTokens->instanceTransforms, matrices.size(),
                    [&](size_t i, size_t index) { transforms[i] = matrices[index]; });

    auto vectors = [&](TfToken const& name) {
        HdHairFloats floats;
        VtValue authored = lookup(name);
        if (authored.IsEmpty()) return floats;
        if (!HdHairToFloats(authored, &floats) || floats.tupleSize != 3) {
            TF_WARN("hdHair: %s.%s: expected 3-vectors, got %s; ignored", id.GetText(), name.GetText(),
                    authored.GetTypeName().c_str());
            floats.values.clear();
        }
        return floats;
    };
    HdHairFloats scales = vectors(HdInstancerTokens->instanceScales);
    forEachInstance(HdInstancerTokens->instanceScales, scales.values.size() / 3, [&](size_t i, size_t index) {
        GfMatrix4d scale(1.0);
        scale.SetScale(GfVec3d(scales.values[3 * index], scales.values[3 * index + 1], scales.values[3 * index + 2]));
        transforms[i] = transforms[i] * scale;
    });

    std::vector<GfQuatd> rotations;
    value = lookup(HdInstancerTokens->instanceRotations);
    if (!value.IsEmpty() && !toQuaternions(value, &rotations))
        TF_WARN("hdHair: %s.%s: expected quaternions, got %s; ignored", id.GetText(),
                HdInstancerTokens->instanceRotations.GetText(), value.GetTypeName().c_str());
    forEachInstance(HdInstancerTokens->instanceRotations, rotations.size(), [&](size_t i, size_t index) {
        GfQuatd q = rotations[index];
        // A zero quaternion (bad data) would collapse the instance: identity instead.
        if (q.GetLength() == 0.0 || !std::isfinite(q.GetLength())) return;
        GfMatrix4d rotate(1.0);
        rotate.SetRotate(q.GetNormalized());
        transforms[i] = transforms[i] * rotate;
    });

    HdHairFloats translations = vectors(HdInstancerTokens->instanceTranslations);
    forEachInstance(HdInstancerTokens->instanceTranslations, translations.values.size() / 3,
                    [&](size_t i, size_t index) {
                        GfMatrix4d translate(1.0);
                        translate.SetTranslate(GfVec3d(translations.values[3 * index],
                                                       translations.values[3 * index + 1],
                                                       translations.values[3 * index + 2]));
                        transforms[i] = transforms[i] * translate;
                    });

    for (GfMatrix4d& transform : transforms) transform = transform * instancerTransform;
    return transforms;
}

std::vector<GfMatrix4d> HdHairInstancer::ComputeInstanceTransforms(SdfPath const& prototypeId) {
    std::vector<GfMatrix4d> local = _ComputeLocalTransforms(prototypeId);
    if (GetParentId().IsEmpty()) return local;
    auto* parent = static_cast<HdHairInstancer*>(GetDelegate()->GetRenderIndex().GetInstancer(GetParentId()));
    if (!parent) {
        TF_WARN("hdHair: %s: parent instancer %s is missing; its transforms are ignored", GetId().GetText(),
                GetParentId().GetText());
        return local;
    }
    // Each parent instance holds every instance of this level: parent-major,
    // as hdEmbree lays them out.
    std::vector<GfMatrix4d> parents = parent->ComputeInstanceTransforms(GetId());
    std::vector<GfMatrix4d> nested;
    nested.reserve(parents.size() * local.size());
    for (GfMatrix4d const& outer : parents)
        for (GfMatrix4d const& inner : local) nested.push_back(inner * outer);
    return nested;
}

PXR_NAMESPACE_CLOSE_SCOPE
