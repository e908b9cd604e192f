#pragma once
// HdHairBasisCurves: a BasisCurves rprim. Sync runs on Hydra's worker threads
// in parallel with other prims and never touches GL: it pulls what the dirty
// bits say changed into the engine's CurvesPrim it keeps, and publishes a
// copy to the render param's scene. Primvar counts are not checked here: the
// engine's curve preparation resolves them with the same rules (and
// messages) as for the embedded .usda reader.

#include "pxr/imaging/hd/basisCurves.h"

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

    hdhair::CurvesPrim _curves;
    std::vector<int> _curveIndices;  // topology indices (rare: UsdImaging sends none)
    int _refineLevel = 0;
};

PXR_NAMESPACE_CLOSE_SCOPE
