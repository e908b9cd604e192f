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

// An instancer's transform primvars, read for one prototype's instances:
// a value of the wrong type is ignored with a warning.
class InstancePrimvarReader {
public:
    InstancePrimvarReader(SdfPath const& id, std::map<TfToken, VtValue> const& primvars, VtIntArray const& indices)
        : _id(id), _primvars(primvars), _indices(indices) {}

    // Calls compose(instance, index) for each instance whose index is below
    // `count`; the others keep the identity for that part, with one warning.
    template <typename Compose>
    void forEachInstance(TfToken const& name, size_t count, Compose&& compose) const {
        if (!_primvars.count(name)) return;
        size_t missing = 0;
        for (size_t i = 0; i < _indices.size(); ++i) {
            int index = _indices[i];
            if (index < 0 || size_t(index) >= count) {
                ++missing;
                continue;
            }
            compose(i, size_t(index));
        }
        if (missing)
            TF_WARN("hdHair: %s.%s: %zu instances have no value (%zu given); they use the identity there",
                    _id.GetText(), name.GetText(), missing, count);
    }

    std::vector<GfMatrix4d> matrices() const {
        return converted<GfMatrix4d>(HdInstancerTokens->instanceTransforms, toMatrices, "matrices");
    }

    std::vector<GfQuatd> rotations() const {
        return converted<GfQuatd>(HdInstancerTokens->instanceRotations, toQuaternions, "quaternions");
    }

    // Scales or translations.
    HdHairFloats vectors(TfToken const& name) const {
        HdHairFloats floats;
        VtValue authored = lookup(name);
        if (authored.IsEmpty()) return floats;
        if (!HdHairToFloats(authored, &floats) || floats.tupleSize != 3) {
            TF_WARN("hdHair: %s.%s: expected 3-vectors, got %s; ignored", _id.GetText(), name.GetText(),
                    authored.GetTypeName().c_str());
            floats.values.clear();
        }
        return floats;
    }

private:
    // The primvar `name` as a vector of T (`convert`), warned and empty when
    // it holds something else.
    template <typename T, typename Convert>
    std::vector<T> converted(TfToken const& name, Convert convert, const char* expected) const {
        std::vector<T> result;
        VtValue value = lookup(name);
        if (!value.IsEmpty() && !convert(value, &result))
            TF_WARN("hdHair: %s.%s: expected %s, got %s; ignored", _id.GetText(), name.GetText(), expected,
                    value.GetTypeName().c_str());
        return result;
    }

    VtValue lookup(TfToken const& name) const {
        auto found = _primvars.find(name);
        return found == _primvars.end() ? VtValue() : found->second;
    }

    SdfPath const& _id;
    std::map<TfToken, VtValue> const& _primvars;
    VtIntArray const& _indices;
};

void applyInstanceMatrices(InstancePrimvarReader const& reader, std::vector<GfMatrix4d>& transforms) {
    const std::vector<GfMatrix4d> matrices = reader.matrices();
    reader.forEachInstance(HdInstancerTokens->instanceTransforms, matrices.size(),
                           [&](size_t i, size_t index) { transforms[i] = matrices[index]; });
}

void applyScales(InstancePrimvarReader const& reader, std::vector<GfMatrix4d>& transforms) {
    HdHairFloats scales = reader.vectors(HdInstancerTokens->instanceScales);
    reader.forEachInstance(HdInstancerTokens->instanceScales, scales.values.size() / 3, [&](size_t i, size_t index) {
        GfMatrix4d scale(1.0);
        scale.SetScale(GfVec3d(scales.values[3 * index], scales.values[3 * index + 1], scales.values[3 * index + 2]));
        transforms[i] = transforms[i] * scale;
    });
}

void applyRotations(InstancePrimvarReader const& reader, std::vector<GfMatrix4d>& transforms) {
    std::vector<GfQuatd> rotations = reader.rotations();
    reader.forEachInstance(HdInstancerTokens->instanceRotations, rotations.size(), [&](size_t i, size_t index) {
        GfQuatd q = rotations[index];
        // A zero quaternion (bad data) would collapse the instance: identity instead.
        if (q.GetLength() == 0.0 || !std::isfinite(q.GetLength())) return;
        GfMatrix4d rotate(1.0);
        rotate.SetRotate(q.GetNormalized());
        transforms[i] = transforms[i] * rotate;
    });
}

void applyTranslations(InstancePrimvarReader const& reader, std::vector<GfMatrix4d>& transforms) {
    HdHairFloats translations = reader.vectors(HdInstancerTokens->instanceTranslations);
    reader.forEachInstance(HdInstancerTokens->instanceTranslations, translations.values.size() / 3,
                           [&](size_t i, size_t index) {
                               GfMatrix4d translate(1.0);
                               translate.SetTranslate(GfVec3d(translations.values[3 * index],
                                                              translations.values[3 * index + 1],
                                                              translations.values[3 * index + 2]));
                               transforms[i] = transforms[i] * translate;
                           });
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
    const InstancePrimvarReader reader(id, _transformPrimvars, indices);
    applyInstanceMatrices(reader, transforms);
    applyScales(reader, transforms);
    applyRotations(reader, transforms);
    applyTranslations(reader, transforms);

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
