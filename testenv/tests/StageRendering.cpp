#include "StageRendering.h"

#include <map>

#include "hdHair/render/CameraView.h"
#include "hdHair/scene/Scene.h"
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

StageRender renderStage(const StageRenderRequest& request, gl::GlBackend backend) {
    Diagnostics diagnostics;
    Scene scene;
    usda::readSceneFile(sourcePath(request.stagePath), request.time, scene, diagnostics);
    RenderSettings settings;
    for (const std::string& assignment : request.settings) settings.setFromAssignment(assignment);
    Renderer& renderer = sharedRenderer(backend);
    CameraView camera;
    if (!request.camera.empty()) {
        const CameraPrim* prim = scene.findCamera(request.camera);
        if (!prim) throw std::runtime_error(request.stagePath + ": no camera " + request.camera);
        camera = cameraViewFromPrim(*prim, request.imageWidth);
    } else {
        SceneBounds bounds = renderer.prepare(scene, diagnostics);
        camera = frameBounds(bounds.min, bounds.max, scene.info().upAxis, request.imageWidth, FramingStyle::FitAll);
    }
    StageRender render;
    render.result = renderer.render(scene, camera, settings, diagnostics);
    render.warnings = diagnostics.warnings();
    return render;
}

double coverage(const Image& rgba) {
    size_t covered = 0, pixels = size_t(rgba.width) * size_t(rgba.height);
    for (size_t p = 0; p < pixels; ++p) covered += rgba.pixels[p * 4 + 3] > 0.0f ? 1 : 0;
    return pixels ? double(covered) / double(pixels) : 0.0;
}

}  // namespace hdhair::testenv
