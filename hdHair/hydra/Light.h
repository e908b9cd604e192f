#pragma once
// HdHairLight: every light sprim hdHair supports (distant, sphere, rect,
// disk, dome, and the simpleLight hosts add at the camera), translated into
// the engine's LightPrim by hdHair/hydra/HydraLights.h.

#include "pxr/imaging/hd/light.h"

PXR_NAMESPACE_OPEN_SCOPE

class HdHairLight final : public HdLight {
public:
    HdHairLight(SdfPath const& id, TfToken const& lightType);
    ~HdHairLight() override = default;

    HdDirtyBits GetInitialDirtyBitsMask() const override;
    void Sync(HdSceneDelegate* sceneDelegate, HdRenderParam* renderParam, HdDirtyBits* dirtyBits) override;
    void Finalize(HdRenderParam* renderParam) override;

private:
    TfToken _lightType;
};

PXR_NAMESPACE_CLOSE_SCOPE
