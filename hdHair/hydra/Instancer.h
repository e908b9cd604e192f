#pragma once
// HdHairInstancer: a Hydra instancer (native instancing and PointInstancers).
// It keeps the instance-rate transform primvars and composes, for each
// prototype, one instance-to-world transform per instance, nested
// instancers included, in the order hdEmbree and Storm use for instanceId.
//
// Hydra does not sync instancers itself: each prototype rprim calls
// HdInstancer::_SyncInstancerAndParents from its own Sync, which syncs the
// instancer (under the instancer's lock) before the rprim reads it.

#include <map>
#include <vector>

#include "pxr/base/gf/matrix4d.h"
#include "pxr/base/vt/value.h"
#include "pxr/imaging/hd/instancer.h"

PXR_NAMESPACE_OPEN_SCOPE

class HdHairInstancer final : public HdInstancer {
public:
    HdHairInstancer(HdSceneDelegate* delegate, SdfPath const& id);

    void Sync(HdSceneDelegate* sceneDelegate, HdRenderParam* renderParam, HdDirtyBits* dirtyBits) override;

    // One transform per instance of `prototypeId`, each placing the
    // prototype's object space (after the prototype's own transform) in the
    // world: instancer transform x translate x rotate x scale x
    // instanceTransform, then the parent instancers'. Instances whose data
    // is missing or malformed get the identity for that part, with a warning.
    std::vector<GfMatrix4d> ComputeInstanceTransforms(SdfPath const& prototypeId);

private:
    std::vector<GfMatrix4d> _ComputeLocalTransforms(SdfPath const& prototypeId) const;

    // hydra:instanceTranslations, Rotations, Scales and Transforms, as authored.
    std::map<TfToken, VtValue> _transformPrimvars;
};

PXR_NAMESPACE_CLOSE_SCOPE
