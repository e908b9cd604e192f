#pragma once
// What curves and meshes pull from a scene delegate the same way: their
// primvars (every interpolation but instance, indexed or not) and, for a
// prototype of an instancer, one world transform per instance. Sync runs on
// Hydra's worker threads; nothing here touches GL.

#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "pxr/base/gf/matrix4d.h"
#include "pxr/base/vt/value.h"
#include "pxr/imaging/hd/changeTracker.h"
#include "pxr/imaging/hd/enums.h"
#include "pxr/imaging/hd/sceneDelegate.h"

#include <glm/mat4x4.hpp>

#include "hdHair/scene/Primvar.h"

PXR_NAMESPACE_OPEN_SCOPE

hdhair::Interpolation HdHairToEngine(HdInterpolation interpolation);

// One primvar as the delegate hands it over.
struct HdHairPulledPrimvar {
    std::string name;
    HdInterpolation interpolation = HdInterpolationConstant;
    VtValue value;
    VtIntArray indices;  // empty when not indexed
};

// Calls `take` for each primvar of `id` that `bits` marks dirty, and returns
// the names of every primvar the delegate describes (dirty or not).
std::set<std::string> HdHairPullPrimvars(HdSceneDelegate* delegate, SdfPath const& id, HdDirtyBits bits,
                                         std::function<void(HdHairPulledPrimvar&)> const& take);

// A numeric primvar as the engine's (Hydra always states the
// interpolation); false for tokens, strings and other non-numeric values.
bool HdHairToEnginePrimvar(HdHairPulledPrimvar& pulled, hdhair::Primvar* out);

// Drops the primvars `present` no longer names.
void HdHairEraseMissingPrimvars(std::map<std::string, hdhair::Primvar>& primvars, std::set<std::string> const& present);

// For a prim whose instancer is `instancerId` (after HdRprim::
// _UpdateInstancer): each instance's world transform, instance x the prim's
// own (`primTransform`), recomputed when the instancer, the instance
// indices or the transform are dirty; reset when the prim is not instanced;
// empty, with a warning, when the instancer is missing.
void HdHairSyncInstanceTransforms(HdSceneDelegate* delegate, SdfPath const& id, SdfPath const& instancerId,
                                  HdDirtyBits bits, GfMatrix4d const& primTransform,
                                  std::optional<std::vector<glm::dmat4>>& instanceTransforms);

PXR_NAMESPACE_CLOSE_SCOPE
