#pragma once
// The scene hdHair renders, exported once for Blender's Cycles: the same
// prims after reading, composition, framing and every repair, so the two
// renderers never disagree about the input (docs/cycles-reference.md).
//
// On disk it is a folder of two files, read by hdHair/reference/cycles/
// renderCyclesScene.py inside Blender:
//  - scene.json: camera, render options, lights, domes, and per prim its
//    material and where its arrays lie in scene.bin (byte offset, count);
//  - scene.bin: the arrays, little-endian float32 and int32, back to back.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hdHair/reference/CyclesCamera.h"
#include "hdHair/reference/CyclesLights.h"
#include "hdHair/reference/CyclesStrands.h"
#include "hdHair/plan/CameraView.h"
#include "hdHair/plan/FramingBounds.h"

namespace hdhair {

class Diagnostics;
class RenderSettings;
class Scene;

// What the path tracer is asked to do; recorded in the EXR's metadata.
struct CyclesRenderOptions {
    int samples = 64;         // per pixel
    int seed = 0;             // Cycles' sampling seed
    // Scattering events after the first: 0 is single scattering (direct
    // light only); every bounce type (diffuse, glossy, transmission) gets
    // this limit. Transparency (opacity below 1) is never limited by it.
    int maxBounces = 64;
    double timeLimitSeconds = 0.0;  // 0: none; else Cycles stops at the sample it is on
    // Samples of each hdHair span handed to Cycles (CyclesStrands.h).
    int pointsPerSpan = 4;
    int threads = 0;          // 0: every core
};

struct CyclesMeshExport {
    std::string path;
    std::vector<float> positions;  // 3 per corner, 3 corners per triangle, world space
    std::vector<float> normals;    // 3 per corner
    std::vector<float> colors;     // 3 per corner, the rendering space
};

struct CyclesScene {
    CyclesCamera camera;
    CyclesLighting lighting;
    std::vector<CyclesStrands> strands;
    std::vector<CyclesMeshExport> meshes;
    CyclesRenderOptions options;
    size_t curves = 0, keys = 0, triangles = 0;
};

// The camera of the exported frame: a camera prim's view, or, for a stage
// rendered without one, the framing camera of the prepared prims' bounds
// (FramingBounds.h: outliers left out), as hdhair-record frames its own.
struct CyclesFraming {
    std::optional<CameraView> camera;
    std::function<CameraView(const SceneBounds& bounds)> frame;
};

// Reads every visible curves and mesh prim as the renderer prepares it
// (repairs reported to `diagnostics`, naming prim and attribute), with the
// lights the frame would be shaded by. `view` receives the camera used.
CyclesScene exportCyclesScene(const Scene& scene, const CyclesFraming& framing, const RenderSettings& settings,
                              const CyclesRenderOptions& options, Diagnostics& diagnostics,
                              CameraView* view = nullptr);

// scene.json's contents (without the arrays), for tests and --explain.
nlohmann::json describeCyclesScene(const CyclesScene& scene);

// Writes scene.json and scene.bin into `folder` (which must exist). Throws
// std::runtime_error naming the file when a write fails.
void writeCyclesScene(const CyclesScene& scene, const std::filesystem::path& folder);

}  // namespace hdhair
