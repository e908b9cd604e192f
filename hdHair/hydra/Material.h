#pragma once
// HdHairMaterial: accepted so that hosts populate materials and bindings, and
// so a later shading issue can read hair parameters from them. hdHair shades
// with displayColor and its render settings for now: every material, bound
// or not, means "built-in hair shading".

#include "pxr/imaging/hd/material.h"

PXR_NAMESPACE_OPEN_SCOPE

class HdHairMaterial final : public HdMaterial {
public:
    explicit HdHairMaterial(SdfPath const& id) : HdMaterial(id) {}
    ~HdHairMaterial() override = default;

    HdDirtyBits GetInitialDirtyBitsMask() const override { return AllDirty; }
    void Sync(HdSceneDelegate*, HdRenderParam*, HdDirtyBits* dirtyBits) override { *dirtyBits = Clean; }
};

PXR_NAMESPACE_CLOSE_SCOPE
