#include "hdHair/hydra/Mesh.h"

#include "pxr/base/tf/diagnostic.h"
#include "pxr/imaging/hd/changeTracker.h"
#include "pxr/imaging/hd/meshTopology.h"
#include "pxr/imaging/hd/sceneDelegate.h"
#include "pxr/imaging/hd/tokens.h"

#include "hdHair/hydra/HydraCamera.h"
#include "hdHair/hydra/RenderParam.h"
#include "hdHair/hydra/RprimSync.h"

PXR_NAMESPACE_OPEN_SCOPE

namespace {

template <typename T, typename Array>
std::vector<T> toVector(Array const& array) {
    return std::vector<T>(array.begin(), array.end());
}

}  // namespace

HdHairMesh::HdHairMesh(SdfPath const& id) : HdMesh(id) { _mesh.path = id.GetString(); }

HdDirtyBits HdHairMesh::GetInitialDirtyBitsMask() const {
    return HdChangeTracker::Clean | HdChangeTracker::InitRepr | HdChangeTracker::DirtyPoints |
           HdChangeTracker::DirtyTopology | HdChangeTracker::DirtySubdivTags | HdChangeTracker::DirtyTransform |
           HdChangeTracker::DirtyVisibility | HdChangeTracker::DirtyPrimvar | HdChangeTracker::DirtyDisplayStyle |
           HdChangeTracker::DirtyInstancer | HdChangeTracker::DirtyInstanceIndex | HdChangeTracker::DirtyPrimID;
}

void HdHairMesh::_InitRepr(TfToken const& reprToken, HdDirtyBits*) {
    auto found = std::find_if(_reprs.begin(), _reprs.end(), _ReprComparator(reprToken));
    if (found == _reprs.end()) _reprs.emplace_back(reprToken, HdReprSharedPtr());
}

void HdHairMesh::Sync(HdSceneDelegate* sceneDelegate, HdRenderParam* renderParam, HdDirtyBits* dirtyBits,
                      TfToken const&) {
    SdfPath const& id = GetId();
    HdDirtyBits const bits = *dirtyBits;
    if (HdChangeTracker::IsVisibilityDirty(bits, id)) _UpdateVisibility(sceneDelegate, dirtyBits);
    _mesh.visible = IsVisible();
    if (HdChangeTracker::IsPrimIdDirty(bits, id) || _mesh.primId < 0) _mesh.primId = GetPrimId();
    if (HdChangeTracker::IsTransformDirty(bits, id)) {
        _primTransform = sceneDelegate->GetTransform(id);
        _mesh.worldTransform = hdhair::hydra::matrixFromGf(_primTransform.data());
    }
    _UpdateInstancer(sceneDelegate, dirtyBits);
    HdHairSyncInstanceTransforms(sceneDelegate, id, GetInstancerId(), bits, _primTransform, _instanceTransforms);
    // Storm's refine level, per prim: usdview's complexity sets it.
    if (HdChangeTracker::IsDisplayStyleDirty(bits, id)) _mesh.refineLevel = GetDisplayStyle(sceneDelegate).refineLevel;
    _SyncTopology(sceneDelegate, bits);
    if (HdChangeTracker::IsAnyPrimvarDirty(bits, id)) _SyncPrimvars(sceneDelegate, bits);
    static_cast<HdHairRenderParam*>(renderParam)->SetMesh(this, _mesh, _instanceTransforms);
    *dirtyBits &= ~HdChangeTracker::AllSceneDirtyBits;
}

void HdHairMesh::_SyncTopology(HdSceneDelegate* sceneDelegate, HdDirtyBits bits) {
    SdfPath const& id = GetId();
    if (HdChangeTracker::IsTopologyDirty(bits, id)) {
        HdMeshTopology const topology = GetMeshTopology(sceneDelegate);
        _mesh.faceVertexCounts = toVector<int>(topology.GetFaceVertexCounts());
        _mesh.faceVertexIndices = toVector<int>(topology.GetFaceVertexIndices());
        _mesh.subdivisionScheme = topology.GetScheme().GetString();
        _mesh.orientation = topology.GetOrientation().GetString();
        _mesh.holeIndices = toVector<int>(topology.GetHoleIndices());
    }
    if (HdChangeTracker::IsSubdivTagsDirty(bits, id)) {
        PxOsdSubdivTags const tags = GetSubdivTags(sceneDelegate);
        _mesh.interpolateBoundary = tags.GetVertexInterpolationRule().GetString();
        _mesh.faceVaryingLinearInterpolation = tags.GetFaceVaryingInterpolationRule().GetString();
        _mesh.triangleSubdivisionRule = tags.GetTriangleSubdivision().GetString();
        _mesh.creaseIndices = toVector<int>(tags.GetCreaseIndices());
        _mesh.creaseLengths = toVector<int>(tags.GetCreaseLengths());
        _mesh.creaseSharpnesses = toVector<float>(tags.GetCreaseWeights());
        _mesh.cornerIndices = toVector<int>(tags.GetCornerIndices());
        _mesh.cornerSharpnesses = toVector<float>(tags.GetCornerWeights());
        // UsdImaging hands over empty tokens for unauthored rules: USD's fallbacks.
        if (_mesh.interpolateBoundary.empty()) _mesh.interpolateBoundary = "edgeAndCorner";
        if (_mesh.faceVaryingLinearInterpolation.empty()) _mesh.faceVaryingLinearInterpolation = "cornersPlus1";
        if (_mesh.triangleSubdivisionRule.empty()) _mesh.triangleSubdivisionRule = "catmullClark";
    }
}

void HdHairMesh::_SyncPrimvars(HdSceneDelegate* sceneDelegate, HdDirtyBits bits) {
    SdfPath const& id = GetId();
    std::set<std::string> const present = HdHairPullPrimvars(sceneDelegate, id, bits, [&](HdHairPulledPrimvar& pulled) {
        hdhair::Primvar primvar;
        if (!HdHairToEnginePrimvar(pulled, &primvar)) {
            _mesh.primvars.erase(pulled.name);  // tokens and strings serve materials
            return;
        }
        if (pulled.name != HdTokens->points.GetString()) {
            _mesh.primvars[pulled.name] = std::move(primvar);
            return;
        }
        _mesh.points.clear();
        if (primvar.tupleSize != 3) {
            TF_WARN("hdHair: %s.points: expected 3 components a point, got %s; mesh not drawn", id.GetText(),
                    primvar.typeName.c_str());
            return;
        }
        for (size_t p = 0; p + 2 < primvar.values.size(); p += 3)
            _mesh.points.emplace_back(primvar.values[p], primvar.values[p + 1], primvar.values[p + 2]);
    });
    HdHairEraseMissingPrimvars(_mesh.primvars, present);
}

void HdHairMesh::Finalize(HdRenderParam* renderParam) {
    static_cast<HdHairRenderParam*>(renderParam)->Remove(GetId().GetString());
}

PXR_NAMESPACE_CLOSE_SCOPE
