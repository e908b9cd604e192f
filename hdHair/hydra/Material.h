#pragma once
// HdHairMaterial: a material sprim. hdHair shades hair with its own models;
// from a material it reads what Storm would show on curves, a
// UsdPreviewSurface's diffuseColor and opacity (values or primvar readers),
// into the engine's scene, where the renderer applies it to every prim bound
// to it (hdHair/curves/StrandColorSource.h). Editing a material re-colours
// its prims without re-syncing them. Other surface shaders leave the prims'
// own colours in place.

#include "pxr/imaging/hd/material.h"

PXR_NAMESPACE_OPEN_SCOPE

class HdHairMaterial final : public HdMaterial {
public:
    explicit HdHairMaterial(SdfPath const& id) : HdMaterial(id) {}
    ~HdHairMaterial() override = default;

    HdDirtyBits GetInitialDirtyBitsMask() const override { return AllDirty; }
    void Sync(HdSceneDelegate* sceneDelegate, HdRenderParam* renderParam, HdDirtyBits* dirtyBits) override;
    void Finalize(HdRenderParam* renderParam) override;
};

PXR_NAMESPACE_CLOSE_SCOPE
