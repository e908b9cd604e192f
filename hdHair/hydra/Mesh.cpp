#include "hdHair/hydra/Mesh.h"

#include "pxr/imaging/hd/changeTracker.h"
#include "pxr/imaging/hd/meshTopology.h"
#include "pxr/imaging/hd/sceneDelegate.h"
#include "pxr/imaging/hd/tokens.h"

#include "hdHair/hydra/HydraCamera.h"
#include "hdHair/hydra/RenderParam.h"
#include "hdHair/hydra/VtValueConversion.h"

PXR_NAMESPACE_OPEN_SCOPE

HdHairMesh::HdHairMesh(SdfPath const& id) : HdMesh(id) { _mesh.path = id.GetString(); }

HdDirtyBits HdHairMesh::GetInitialDirtyBitsMask() const {
    return HdChangeTracker::Clean | HdChangeTracker::InitRepr | HdChangeTracker::DirtyPoints |
           HdChangeTracker::DirtyTopology | HdChangeTracker::DirtyTransform | HdChangeTracker::DirtyVisibility |
           HdChangeTracker::DirtyPrimvar;
}

void HdHairMesh::_InitRepr(TfToken const& reprToken, HdDirtyBits*) {
    auto found = std::find_if(_reprs.begin(), _reprs.end(), _ReprComparator(reprToken));
    if (found == _reprs.end()) _reprs.emplace_back(reprToken, HdReprSharedPtr());
}

void HdHairMesh::Sync(HdSceneDelegate* sceneDelegate, HdRenderParam* renderParam, HdDirtyBits* dirtyBits,
                      TfToken const&) {
    SdfPath const& id = GetId();
    HdDirtyBits bits = *dirtyBits;
    if (HdChangeTracker::IsVisibilityDirty(bits, id)) _UpdateVisibility(sceneDelegate, dirtyBits);
    _mesh.visible = IsVisible();
    if (HdChangeTracker::IsTransformDirty(bits, id)) {
        GfMatrix4d toWorld = sceneDelegate->GetTransform(id);
        _mesh.worldTransform = hdhair::hydra::matrixFromGf(toWorld.data());
    }
    if (HdChangeTracker::IsTopologyDirty(bits, id)) {
        HdMeshTopology topology = GetMeshTopology(sceneDelegate);
        VtIntArray const& counts = topology.GetFaceVertexCounts();
        VtIntArray const& indices = topology.GetFaceVertexIndices();
        _mesh.faceVertexCounts.assign(counts.begin(), counts.end());
        _mesh.faceVertexIndices.assign(indices.begin(), indices.end());
        _mesh.subdivisionScheme = topology.GetScheme().GetString();
    }
    if (HdChangeTracker::IsPrimvarDirty(bits, id, HdTokens->points)) {
        HdHairFloats floats;
        _mesh.points.clear();
        if (HdHairToFloats(sceneDelegate->Get(id, HdTokens->points), &floats) && floats.tupleSize == 3)
            for (size_t p = 0; p + 2 < floats.values.size(); p += 3)
                _mesh.points.emplace_back(floats.values[p], floats.values[p + 1], floats.values[p + 2]);
    }
    static_cast<HdHairRenderParam*>(renderParam)->SetMesh(this, _mesh);
    *dirtyBits &= ~HdChangeTracker::AllSceneDirtyBits;
}

void HdHairMesh::Finalize(HdRenderParam* renderParam) {
    static_cast<HdHairRenderParam*>(renderParam)->Remove(GetId().GetString());
}

PXR_NAMESPACE_CLOSE_SCOPE
