#include "hdHair/hydra/RendererPlugin.h"

#include <mutex>

#include "pxr/base/tf/diagnostic.h"
#include "pxr/imaging/hd/rendererPluginRegistry.h"

#include "hdHair/gl/GlRenderThread.h"
#include "hdHair/hydra/RenderDelegate.h"

PXR_NAMESPACE_OPEN_SCOPE

TF_REGISTRY_FUNCTION(TfType) { HdRendererPluginRegistry::Define<HdHairRendererPlugin>(); }

HdRenderDelegate* HdHairRendererPlugin::CreateRenderDelegate() { return new HdHairRenderDelegate(); }

HdRenderDelegate* HdHairRendererPlugin::CreateRenderDelegate(HdRenderSettingsMap const& settingsMap) {
    return new HdHairRenderDelegate(settingsMap);
}

void HdHairRendererPlugin::DeleteRenderDelegate(HdRenderDelegate* renderDelegate) { delete renderDelegate; }

bool HdHairRendererPlugin::IsSupported(bool) const {
    static std::once_flag probed;
    static bool supported = false;
    std::call_once(probed, [] {
        try {
            // The probe makes a context on a thread of its own, as rendering
            // will: never on the host's thread (see GlRenderThread.h).
            hdhair::gl::GlRenderThread probe(hdhair::gl::defaultGlBackend());
            supported = true;
        } catch (std::exception const& error) {
            TF_WARN("hdHair is not available: %s", error.what());
        }
    });
    return supported;
}

PXR_NAMESPACE_CLOSE_SCOPE
