#include "hdHair/hydra/RprimSync.h"

#include "pxr/base/tf/diagnostic.h"
#include "pxr/imaging/hd/instancer.h"
#include "pxr/imaging/hd/renderIndex.h"

#include "hdHair/hydra/HydraCamera.h"
#include "hdHair/hydra/Instancer.h"
#include "hdHair/hydra/VtValueConversion.h"

PXR_NAMESPACE_OPEN_SCOPE

hdhair::Interpolation HdHairToEngine(HdInterpolation interpolation) {
    switch (interpolation) {
    case HdInterpolationConstant: return hdhair::Interpolation::Constant;
    case HdInterpolationUniform: return hdhair::Interpolation::Uniform;
    case HdInterpolationVarying: return hdhair::Interpolation::Varying;
    case HdInterpolationVertex: return hdhair::Interpolation::Vertex;
    case HdInterpolationFaceVarying: return hdhair::Interpolation::FaceVarying;
    default: return hdhair::Interpolation::Constant;
    }
}

std::set<std::string> HdHairPullPrimvars(HdSceneDelegate* delegate, SdfPath const& id, HdDirtyBits bits,
                                         std::function<void(HdHairPulledPrimvar&)> const& take) {
    std::set<std::string> present;
    for (int i = HdInterpolationConstant; i < HdInterpolationCount; ++i) {
        HdInterpolation interpolation = HdInterpolation(i);
        if (interpolation == HdInterpolationInstance) continue;
        for (HdPrimvarDescriptor const& descriptor : delegate->GetPrimvarDescriptors(id, interpolation)) {
            present.insert(descriptor.name.GetString());
            if (!HdChangeTracker::IsPrimvarDirty(bits, id, descriptor.name)) continue;
            HdHairPulledPrimvar pulled;
            pulled.name = descriptor.name.GetString();
            pulled.interpolation = interpolation;
            pulled.value = descriptor.indexed ? delegate->GetIndexedPrimvar(id, descriptor.name, &pulled.indices)
                                              : delegate->Get(id, descriptor.name);
            take(pulled);
        }
    }
    return present;
}

bool HdHairToEnginePrimvar(HdHairPulledPrimvar& pulled, hdhair::Primvar* out) {
    HdHairFloats floats;
    if (!HdHairToFloats(pulled.value, &floats)) return false;
    out->name = pulled.name;
    out->typeName = floats.typeName;
    out->tupleSize = floats.tupleSize;
    out->interpolation = HdHairToEngine(pulled.interpolation);
    // Hydra always states the interpolation (UsdImaging fills in USD's defaults).
    out->interpolationAuthored = true;
    out->values = std::move(floats.values);
    out->indices.assign(pulled.indices.begin(), pulled.indices.end());
    return true;
}

void HdHairEraseMissingPrimvars(std::map<std::string, hdhair::Primvar>& primvars,
                                std::set<std::string> const& present) {
    for (auto it = primvars.begin(); it != primvars.end();)
        it = present.count(it->first) ? std::next(it) : primvars.erase(it);
}

void HdHairSyncInstanceTransforms(HdSceneDelegate* delegate, SdfPath const& id, SdfPath const& instancerId,
                                  HdDirtyBits bits, GfMatrix4d const& primTransform,
                                  std::optional<std::vector<glm::dmat4>>& instanceTransforms) {
    if (instancerId.IsEmpty()) {
        instanceTransforms.reset();
        return;
    }
    // Syncs the instancer and its parents if dirty; Hydra leaves that to rprims.
    HdInstancer::_SyncInstancerAndParents(delegate->GetRenderIndex(), instancerId);
    if (instanceTransforms && !HdChangeTracker::IsInstancerDirty(bits, id) &&
        !HdChangeTracker::IsInstanceIndexDirty(bits, id) && !HdChangeTracker::IsTransformDirty(bits, id))
        return;
    auto* instancer = static_cast<HdHairInstancer*>(delegate->GetRenderIndex().GetInstancer(instancerId));
    if (!instancer) {
        TF_WARN("hdHair: %s: instancer %s is missing; prim not drawn", id.GetText(), instancerId.GetText());
        instanceTransforms.emplace();
        return;
    }
    std::vector<glm::dmat4> transforms;
    for (GfMatrix4d const& instance : instancer->ComputeInstanceTransforms(id)) {
        GfMatrix4d const toWorld = primTransform * instance;  // the prim's transform applies first
        transforms.push_back(hdhair::hydra::matrixFromGf(toWorld.data()));
    }
    instanceTransforms = std::move(transforms);
}

PXR_NAMESPACE_CLOSE_SCOPE
