#pragma once
// Renders a stage the way hdhair-record does, in-process, for image tests.

#include <memory>
#include <string>
#include <vector>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/image/Image.h"
#include "hdHair/plan/CameraView.h"
#include "hdHair/plan/RenderSettings.h"
#include "hdHair/render/Renderer.h"
#include "hdHair/scene/Scene.h"

namespace hdhair::testenv {

struct StageRender {
    RenderResult result;
    std::vector<Diagnostic> warnings;  // reading the stage and rendering it
};

struct StageRenderRequest {
    std::string stagePath;           // absolute, or relative to the source tree
    std::string camera;              // "" frames the whole stage
    int imageWidth = 256;
    double time = 0.0;
    std::vector<std::string> settings;  // NAME=VALUE
    Complexity complexity = Complexity::Low;  // hdhair-record's --complexity
    // Moves the image this many pixels right and down: a sub-pixel shift puts
    // strand edges where another CPU's rounding might (edge-jitter checks).
    double pixelShift = 0.0;
};

// One renderer per backend per test process: context creation is the
// expensive part and tests render many stages.
Renderer& sharedRenderer(gl::GlBackend backend = gl::GlBackend::Egl);

// The request's stage at its time, as hdhair-record's embedded reader reads
// it; reading warnings go into `diagnostics`.
Scene readStage(const StageRenderRequest& request, Diagnostics& diagnostics);

// The view the request renders `scene` through: its camera prim, or a camera
// framing the whole stage (which prepares the scene's curves in `renderer`).
CameraView stageCamera(const Scene& scene, const StageRenderRequest& request, Renderer& renderer,
                       Diagnostics& diagnostics);

// The settings the request renders with: its complexity, then its NAME=VALUE assignments.
RenderSettings stageSettings(const StageRenderRequest& request);

// Renders `scene` (the request's stage, perhaps edited) through the request's
// camera, width, settings and complexity.
StageRender renderScene(const Scene& scene, const StageRenderRequest& request,
                        gl::GlBackend backend = gl::GlBackend::Egl);

// readStage, then renderScene.
StageRender renderStage(const StageRenderRequest& request, gl::GlBackend backend = gl::GlBackend::Egl);

// The source tree's root (for stage and baseline paths).
std::string sourcePath(const std::string& relative);

// Fraction of pixels with alpha above zero.
double coverage(const Image& rgba);

}  // namespace hdhair::testenv
