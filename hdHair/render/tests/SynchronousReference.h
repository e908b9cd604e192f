#pragma once
// The image a stopped, resumed or progressive frame must equal: what a fresh
// synchronous Renderer draws for `secondScene` from `secondView` after one
// frame of `firstScene` from `firstView` (so that shadow maps and
// tessellation carried over from the first frame are part of the reference).

#include "hdHair/base/Diagnostics.h"
#include "hdHair/render/Renderer.h"

namespace hdhair::testscenes {

inline RenderResult synchronousSecondFrame(const Scene& firstScene, const CameraView& firstView,
                                           const Scene& secondScene, const CameraView& secondView,
                                           const RenderSettings& settings, Diagnostics& diagnostics) {
    Renderer fresh(gl::defaultGlBackend());
    fresh.render(firstScene, firstView, settings, diagnostics, RenderOutputs{true});
    return fresh.render(secondScene, secondView, settings, diagnostics, RenderOutputs{true});
}

}  // namespace hdhair::testscenes
