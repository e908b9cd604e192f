#pragma once
// Which passes a frame runs, decided per scene before any GL work: only the
// effects a scene calls for are simulated, and what is off costs nothing.
// The plan is a FrameGraph (FrameGraph.h): each pass with what it reads and
// writes and the reason it runs or not, printed by --explain and kept, with
// each pass's time, in --stats.

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "hdHair/render/FrameGraph.h"
#include "hdHair/shading/ShadingLight.h"

namespace hdhair {

class RenderSettings;
class Scene;
struct CameraView;

// How the frame's strands are composited.
enum class TransparencyPath { Opaque, BinSorted, Exact, Unsorted };
const char* toString(TransparencyPath path);

// What the frame's strands need, measured on the prepared curves.
struct StrandSummary {
    uint64_t segments = 0;
    // Every control point fully opaque (1 exactly: then every interpolated
    // opacity is 1 too, Catmull-Rom weights summing to one).
    bool allOpaque = true;
    // The thinnest any strand can project, in pixels, at the far side of the
    // strands' bounds (conservative); infinity when there are none.
    double minProjectedWidthPixels = 0.0;
    bool anyLit = true;          // some prim's material is lit (not flat)
    std::string shadingModels;   // the models in use, e.g. "kajiyaKay+marschner"
    size_t perPointPrims = 0;    // prims whose hair parameters vary per curve or vertex
    size_t analyticPrims = 0;    // Marschner prims shaded with per-fragment azimuthal terms
};

// What the frame's meshes need, measured on the prepared meshes.
struct MeshSummary {
    size_t meshes = 0;        // visible meshes with at least one triangle
    uint64_t triangles = 0;   // after refinement
    int minRefineLevel = 0, maxRefineLevel = 0;  // the levels drawn
    bool changed = false;     // the GPU copy must be sent again
};

// The passes, in the order they run:
//   upload        preparedStrands -> strands        GPU copy of the changed prims
//   meshUpload    preparedMeshes -> meshGeometry    GPU copy of the meshes, when one changed
//   sort          preparedStrands -> drawOrder      binSorted only
//   clear         -> color, depth[, ids]            the frame's targets, empty
//   meshes        meshGeometry, color, depth[, ids] -> color, depth[, ids]   opaque, lights of batch 1
//   strands       strands[, drawOrder], color, depth -> color, depth[, ids]   lights of batch 1
//   ids           strands, depth -> ids             blended paths, when a host asks for ids
//   resolve       color, depth[, ids] (in place)    multisampled frames
//   lightBatch k  [strands[, drawOrder],] [meshGeometry,] color -> color   lights of batch k (k >= 2)
//   readback      color, depth[, ids] -> aovs       the frame's images, to the CPU
//   displayTransform  color -> displayImage         the display image on the GPU, when asked for
// Meshes are drawn first and write depth, so every strand path tests
// against them (NearestStrandRule.h: how their depth and ids combine with
// the strands').
struct RenderPlan {
    FrameGraph graph;
    ShadingLights lights;       // the stage's lights, plus the camera light when used
    bool cameraLight = false;
    TransparencyPath transparency = TransparencyPath::Opaque;
    uint32_t sortBins = 0;      // for BinSorted
    int msaaSamples = 0;        // for Opaque
    bool flatShading = false;   // every prim flat: no lights needed
    bool meshesLit = false;     // meshes shaded with the lights (Lambert), else displayColor unlit
    // Light passes: [begin, end) ranges of `lights.lights`, at most
    // lightsPerPass each; always at least one (ambient and unlit shading
    // need a pass too).
    std::vector<std::pair<size_t, size_t>> lightBatches;

    bool isEnabled(const std::string& name) const { return graph.isEnabled(name); }
    // Exact transparency over its memory budget: the frame is redrawn
    // binSorted with `bins` bins, which needs the ids pass when ids are asked for.
    void fallBackToBinSorted(uint32_t bins, bool idsRequested);
    std::string describe() const { return graph.describe(); }  // for --explain
    nlohmann::json toJson() const;
};

// idsRequested: a host asked for primId/instanceId/elementId. Depth is always
// produced; with blending, by the strand pass (NearestStrandRule.h).
// displayOnGpu: the frame also delivers its display image, made on the GPU.
RenderPlan makeRenderPlan(const Scene& scene, const RenderSettings& settings, const CameraView& camera,
                          const StrandSummary& strands, bool idsRequested = false, const MeshSummary& meshes = {},
                          bool displayOnGpu = false);

}  // namespace hdhair
