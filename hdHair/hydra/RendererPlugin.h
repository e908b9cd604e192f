#pragma once
// HdHairRendererPlugin: registers hdHair with Hydra's renderer plugin
// registry under the display name "HdHair" (plugInfo.json), with a priority
// that never makes it the default over Storm, RenderMan or Embree.

#include "pxr/imaging/hd/rendererPlugin.h"

PXR_NAMESPACE_OPEN_SCOPE

class HdHairRendererPlugin final : public HdRendererPlugin {
public:
    HdHairRendererPlugin() = default;
    ~HdHairRendererPlugin() override = default;

    HdRenderDelegate* CreateRenderDelegate() override;
    HdRenderDelegate* CreateRenderDelegate(HdRenderSettingsMap const& settingsMap) override;
    void DeleteRenderDelegate(HdRenderDelegate* renderDelegate) override;

    // True when hdHair can make its own headless GL context (checked once).
    // The host's GPU mode does not matter: hdHair never uses the host's
    // context, and on a machine without a GPU it renders with llvmpipe.
    bool IsSupported(bool gpuEnabled = true) const override;
};

PXR_NAMESPACE_CLOSE_SCOPE
