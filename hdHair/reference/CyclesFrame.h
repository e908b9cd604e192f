#pragma once
// One frame path-traced by Cycles from the scene hdHair renders: exported
// (CyclesScene.h) into a temporary folder, rendered by Blender
// (CyclesProcess.h) and read back, the folder removed whatever happens.
// hdhair-record --reference cycles writes it as its image; hdhair-bench
// --accuracy --cycles compares hdHair's frames with it.

#include <atomic>
#include <functional>

#include "hdHair/image/Image.h"
#include "hdHair/image/ImageWriter.h"
#include "hdHair/reference/CyclesProcess.h"
#include "hdHair/reference/CyclesScene.h"
#include "hdHair/plan/CameraView.h"

namespace hdhair {

struct CyclesFrameRequest {
    std::string blender = "blender";  // the executable: a path, or a name looked up on PATH
    CyclesRenderOptions options;
    std::function<void(const CyclesProgress&)> progress;
    const std::atomic<bool>* stop = nullptr;
};

struct CyclesFrame {
    Image color;         // RGBA, pre-multiplied, the rendering space
    CameraView camera;   // the view it was rendered from
    nlohmann::json scene;  // describeCyclesScene: what was exported
    size_t curves = 0, keys = 0, triangles = 0, lights = 0, domes = 0;
    CyclesProcessResult result;
    double exportMilliseconds = 0.0;
};

// Throws std::runtime_error with one line when the export, Blender or the
// image read fails, or when Cycles' image is not the camera's size;
// CyclesStopped when `stop` was set.
CyclesFrame renderCyclesFrame(const Scene& scene, const CyclesFraming& framing, const RenderSettings& settings,
                              const CyclesFrameRequest& request, Diagnostics& diagnostics);

// What an EXR of the frame records: the path tracer's settings and what it did.
ImageMetadata cyclesFrameMetadata(const CyclesRenderOptions& options, const CyclesProcessResult& result);

}  // namespace hdhair
