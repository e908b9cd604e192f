#include "hdHair/reference/CyclesFrame.h"

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace hdhair {

namespace {

// The folder a frame's exported scene and Cycles' image live in, removed
// whatever happens (a stopped render leaves nothing behind).
class TemporaryFolder {
public:
    TemporaryFolder() {
        std::string pattern = (std::filesystem::temp_directory_path() / "hdhair-cycles-XXXXXX").string();
        if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot make a temporary folder for Cycles");
        path_ = pattern;
    }
    ~TemporaryFolder() {
        std::error_code ignored;
        std::filesystem::remove_all(path_, ignored);
    }
    TemporaryFolder(const TemporaryFolder&) = delete;
    TemporaryFolder& operator=(const TemporaryFolder&) = delete;
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

}  // namespace

CyclesFrame renderCyclesFrame(const Scene& scene, const CyclesFraming& framing, const RenderSettings& settings,
                              const CyclesFrameRequest& request, Diagnostics& diagnostics) {
    const auto start = std::chrono::steady_clock::now();
    CyclesFrame frame;
    const CyclesScene exported = exportCyclesScene(scene, framing, settings, request.options, diagnostics, &frame.camera);
    TemporaryFolder folder;
    writeCyclesScene(exported, folder.path());
    frame.exportMilliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    frame.scene = describeCyclesScene(exported);
    frame.curves = exported.curves;
    frame.keys = exported.keys;
    frame.triangles = exported.triangles;
    frame.lights = exported.lighting.lights.size();
    frame.domes = exported.lighting.domes.size();

    CyclesProcessRequest process;
    process.blender = request.blender;
    process.script = defaultCyclesScript();
    process.sceneJson = (folder.path() / "scene.json").string();
    process.outputExr = (folder.path() / "cycles.exr").string();
    process.progress = request.progress;
    process.stop = request.stop;
    frame.result = runCyclesProcess(process);
    frame.color = readImage(process.outputExr);
    const CameraView& camera = frame.camera;
    if (frame.color.width != camera.imageWidth || frame.color.height != camera.imageHeight || frame.color.channels != 4)
        throw std::runtime_error(fmt::format("Cycles wrote a {}x{} image of {} channels, not {}x{} RGBA",
                                             frame.color.width, frame.color.height, frame.color.channels,
                                             camera.imageWidth, camera.imageHeight));
    return frame;
}

ImageMetadata cyclesFrameMetadata(const CyclesRenderOptions& options, const CyclesProcessResult& result) {
    return {{"hdhair:reference", "cycles"},
            {"cycles:version", result.blenderVersion},
            {"cycles:samples", std::to_string(options.samples)},
            {"cycles:samplesDone", std::to_string(result.samplesDone)},
            {"cycles:seed", std::to_string(options.seed)},
            {"cycles:maxBounces", std::to_string(options.maxBounces)},
            {"cycles:timeLimit", fmt::format("{}", options.timeLimitSeconds)},
            {"cycles:keysPerSpan", std::to_string(options.pointsPerSpan)},
            {"cycles:renderSeconds", fmt::format("{:.3f}", result.renderSeconds)}};
}

}  // namespace hdhair
