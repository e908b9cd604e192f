#pragma once
// HdHairMesh: a mesh rprim, drawn by the engine as an opaque occluder of the
// hair (hdHair/meshes/README.md). Synced like the curves: in parallel,
// without GL, only what the dirty bits name: points, topology with its
// subdivision tags, holes and orientation, transform, visibility, the refine
// level of its display style (usdview's complexity), primvars at every
// interpolation, and instancing, where each instance becomes an engine prim
// of its own (as for curves). Counts are not checked here: mesh preparation
// does that, with the same rules and messages as for the .usda reader.

#include <optional>
#include <vector>

#include "pxr/imaging/hd/mesh.h"

#include <glm/mat4x4.hpp>

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
    void _SyncTopology(HdSceneDelegate* sceneDelegate, HdDirtyBits bits);
    void _SyncPrimvars(HdSceneDelegate* sceneDelegate, HdDirtyBits bits);

    hdhair::MeshPrim _mesh;
    std::optional<std::vector<glm::dmat4>> _instanceTransforms;
    GfMatrix4d _primTransform{1.0};
};

PXR_NAMESPACE_CLOSE_SCOPE
