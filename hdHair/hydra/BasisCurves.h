#pragma once
// HdHairBasisCurves: a BasisCurves rprim. Sync runs on Hydra's worker threads
// in parallel with other prims and never touches GL: it pulls what the dirty
// bits say changed into the engine's CurvesPrim it keeps, and publishes a
// copy to the render param's scene. Primvar counts are not checked here: the
// engine's curve preparation resolves them with the same rules (and
// messages) as for the embedded .usda reader.

#include <optional>
#include <vector>

#include "pxr/imaging/hd/basisCurves.h"

#include <glm/mat4x4.hpp>

#include "hdHair/scene/CurvesPrim.h"

PXR_NAMESPACE_OPEN_SCOPE

class HdHairBasisCurves final : public HdBasisCurves {
public:
    explicit HdHairBasisCurves(SdfPath const& id);
    ~HdHairBasisCurves() override = default;

    HdDirtyBits GetInitialDirtyBitsMask() const override;
    void Sync(HdSceneDelegate* sceneDelegate, HdRenderParam* renderParam, HdDirtyBits* dirtyBits,
              TfToken const& reprToken) override;
    void Finalize(HdRenderParam* renderParam) override;

protected:
    HdDirtyBits _PropagateDirtyBits(HdDirtyBits bits) const override;
    void _InitRepr(TfToken const& reprToken, HdDirtyBits* dirtyBits) override;

private:
    void _SyncTopology(HdSceneDelegate* sceneDelegate);
    void _SyncPrimvars(HdSceneDelegate* sceneDelegate, HdDirtyBits dirtyBits);
    void _SyncInstances(HdSceneDelegate* sceneDelegate, HdDirtyBits* dirtyBits);

    hdhair::CurvesPrim _curves;
    std::vector<int> _curveIndices;  // topology indices (rare: UsdImaging sends none)
    int _refineLevel = 0;
    // For a prototype of an instancer: each instance's world transform
    // (instance x the prim's own); nullopt when the prim is not instanced.
    std::optional<std::vector<glm::dmat4>> _instanceTransforms;
    GfMatrix4d _primTransform{1.0};
};

PXR_NAMESPACE_CLOSE_SCOPE
