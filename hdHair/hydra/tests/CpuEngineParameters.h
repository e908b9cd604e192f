#pragma once
// UsdImagingGLEngine parameters for the plugin's tests: no GPU (no Storm, no
// GL interop), so HdHair renders on its own EGL context and hands its images
// back through the render buffers, as usdrecord --disableGpu does.

#include "pxr/usdImaging/usdImagingGL/engine.h"

inline PXR_NS::UsdImagingGLEngine::Parameters cpuEngineParameters() {
    PXR_NS::UsdImagingGLEngine::Parameters parameters;
    parameters.gpuEnabled = false;
    return parameters;
}
