#pragma once
// HdHairMesh: a mesh rprim, kept in the engine's scene so that heads and
// scalps can occlude hair once the occluder pass exists. Synced like the
// curves: in parallel, without GL, only what is dirty.

#include "pxr/imaging/hd/mesh.h"

#include "hdHair/scene/MeshPrim.h"

PXR_NAMESPACE_OPEN_SCOPE

class HdHairMesh final : public HdMesh {
public:
    explicit HdHairMesh(SdfPath const& id);
    ~HdHairMesh() override = default;

    HdDirtyBits GetInitialDirtyBitsMask() const override;
    void Sync(HdSceneDelegate* sceneDelegate, HdRenderParam* renderParam, HdDirtyBits* dirtyBits,
              TfToken const& reprToken) override;
    void Finalize(HdRenderParam* renderParam) override;

protected:
    HdDirtyBits _PropagateDirtyBits(HdDirtyBits bits) const override { return bits; }
    void _InitRepr(TfToken const& reprToken, HdDirtyBits* dirtyBits) override;

private:
    hdhair::MeshPrim _mesh;
};

PXR_NAMESPACE_CLOSE_SCOPE
