#include "StageRendering.h"

#include <map>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

#include "hdHair/usda/SceneReader.h"

namespace hdhair::testenv {

Renderer& sharedRenderer(gl::GlBackend backend) {
    static std::map<gl::GlBackend, std::unique_ptr<Renderer>> renderers;
    std::unique_ptr<Renderer>& renderer = renderers[backend];
    if (!renderer) renderer = std::make_unique<Renderer>(backend);
    return *renderer;
}

std::string sourcePath(const std::string& relative) {
    if (!relative.empty() && relative[0] == '/') return relative;
    return std::string(HDHAIR_SOURCE_DIR) + "/" + relative;
}

Scene readStage(const StageRenderRequest& request, Diagnostics& diagnostics) {
    Scene scene;
    usda::readSceneFile(sourcePath(request.stagePath), request.time, scene, diagnostics);
    return scene;
}

CameraView stageCamera(const Scene& scene, const StageRenderRequest& request, Renderer& renderer,
                       Diagnostics& diagnostics) {
    CameraView camera;
    if (!request.camera.empty()) {
        const CameraPrim* prim = scene.findCamera(request.camera);
        if (!prim) throw std::runtime_error(request.stagePath + ": no camera " + request.camera);
        camera = cameraViewFromPrim(*prim, request.imageWidth);
    } else {
        SceneBounds bounds = renderer.prepare(scene, stageSettings(request), diagnostics);
        camera = frameBounds(bounds.min, bounds.max, scene.info().upAxis, request.imageWidth, FramingStyle::FitAll);
    }
    // Clip space spans 2 over the image's width and height; pixel rows run down.
    glm::dvec3 shift(2.0 * request.pixelShift / camera.imageWidth, -2.0 * request.pixelShift / camera.imageHeight, 0.0);
    camera.projection = glm::translate(glm::dmat4(1.0), shift) * camera.projection;
    return camera;
}

RenderSettings stageSettings(const StageRenderRequest& request) {
    return RenderSettings::fromAssignments(request.complexity, request.settings);
}

StageRender renderScene(const Scene& scene, const StageRenderRequest& request, gl::GlBackend backend) {
    Diagnostics diagnostics;
    Renderer& renderer = sharedRenderer(backend);
    CameraView camera = stageCamera(scene, request, renderer, diagnostics);
    StageRender render;
    // Every image test also checks that each pass touches only what it declares.
    FrameControl control;
    control.checkResourceAccess = true;
    render.result = renderer.render(scene, camera, stageSettings(request), diagnostics, {}, control);
    render.warnings = diagnostics.warnings();
    return render;
}

StageRender renderStage(const StageRenderRequest& request, gl::GlBackend backend) {
    Diagnostics reading;
    Scene scene = readStage(request, reading);
    StageRender render = renderScene(scene, request, backend);
    std::vector<Diagnostic> readingWarnings = reading.warnings();
    render.warnings.insert(render.warnings.begin(), readingWarnings.begin(), readingWarnings.end());
    return render;
}

double coverage(const Image& rgba) {
    size_t covered = 0, pixels = size_t(rgba.width) * size_t(rgba.height);
    for (size_t p = 0; p < pixels; ++p) covered += rgba.pixels[p * 4 + 3] > 0.0f ? 1 : 0;
    return pixels ? double(covered) / double(pixels) : 0.0;
}

}  // namespace hdhair::testenv
