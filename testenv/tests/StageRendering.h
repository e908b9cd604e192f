#pragma once
// Renders a stage the way hdhair-record does, in-process, for image tests.

#include <memory>
#include <string>
#include <vector>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/image/Image.h"
#include "hdHair/render/Renderer.h"

namespace hdhair::testenv {

struct StageRender {
    RenderResult result;
    std::vector<Diagnostic> warnings;
};

struct StageRenderRequest {
    std::string stagePath;           // absolute, or relative to the source tree
    std::string camera;              // "" frames the whole stage
    int imageWidth = 256;
    double time = 0.0;
    std::vector<std::string> settings;  // NAME=VALUE
};

// One renderer per backend per test process: context creation is the
// expensive part and tests render many stages.
Renderer& sharedRenderer(gl::GlBackend backend = gl::GlBackend::Egl);

StageRender renderStage(const StageRenderRequest& request, gl::GlBackend backend = gl::GlBackend::Egl);

// The source tree's root (for stage and baseline paths).
std::string sourcePath(const std::string& relative);

// Fraction of pixels with alpha above zero.
double coverage(const Image& rgba);

}  // namespace hdhair::testenv
