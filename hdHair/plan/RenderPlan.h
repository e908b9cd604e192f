#pragma once
// Which passes a frame runs, decided per scene before any GL work: only the
// effects a scene calls for are simulated, and what is off costs nothing.
// The planners decide the frame's recipe (FrameRecipe.h); the plan holds that
// recipe and the FrameGraph built from it (FrameGraph.h): each pass with its
// kind, what it reads and writes and the reason it runs or not, printed by
// --explain and kept, with each pass's time, in --stats.

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "hdHair/plan/FrameFallback.h"
#include "hdHair/plan/FrameGraph.h"
#include "hdHair/plan/FrameRecipe.h"

namespace hdhair {

struct CameraView;

// The passes, in the order they run, one kind a line (PassKind, in its
// order: RenderPlan.ThePassListHereIsEveryKindInOrder checks this list):
//   upload        preparedStrands -> strands        GPU copy of the changed prims
//   meshUpload    preparedMeshes -> meshGeometry    GPU copy of the meshes, when one changed
//   sort          preparedStrands -> drawOrder      binSorted only, by the hardware rasteriser
//   shadowDepth L      strands -> hairDepth L       per shadow-casting light L: its nearest hair
//   deepOpacity L      strands, hairDepth L -> deepOpacity L   its opacity layers
//   shadowFragments L  strands -> shadowFragments L  shadowMode=reference instead: every fragment
//   meshShadow L       meshGeometry -> meshDepth L  with meshes: the nearest mesh in a view of hair and meshes,
//                 which hides the hair, the other meshes and its own far faces behind it
//                 (a map kept from an earlier frame is an input of the graph instead)
//   opacityMipmaps  deepOpacity of every light -> convolvedOpacity   domeShadowFilter=mipmap, an SRBF light's map read
//   densityVolume preparedStrands -> densityVolume  a light shadowed through it (shadowMode=auto: inside the hair)
//   clear         -> color, depth[, ids]            the frame's targets, empty
//   meshes        meshGeometry, color, depth[, ids, the batch's shadows] -> color, depth[, ids]   opaque, lights of batch 1
//   strands       strands[, drawOrder], color, depth[, the batch's shadows] -> color, depth[, ids]   lights of batch 1
//   ids           strands, depth -> ids             blended paths, when a host asks for ids
//   resolve       color, depth[, ids] (in place)    multisampled frames
//   lightBatch k  [strands[, drawOrder],] [meshGeometry,] color[, the batch's shadows] -> color   lights of batch k (k >= 2)
//   readback      color, depth[, ids] -> aovs       the frame's images, to the CPU
//   displayTransform  color -> displayImage         the display image on the GPU, when asked for
// Meshes are drawn first and write depth, so every strand path tests
// against them (NearestStrandRule.h: how their depth and ids combine with
// the strands').
//
// A plan is made whole and is not changed while its frame runs: the shadow
// maps' slots come in with it (ShadowMapAssignment), and what a pass finds
// the plan could not know (lists over their memory) makes the Renderer plan
// the frame again (FrameFallback.h), never edit this one.
class RenderPlan {
public:
    RenderPlan() = default;
    RenderPlan(FrameRecipe recipe, FrameGraph graph) : recipe_(std::move(recipe)), graph_(std::move(graph)) {}

    const FrameRecipe& recipe() const { return recipe_; }
    const FrameGraph& graph() const { return graph_; }

    bool isEnabled(PassKind kind, size_t subject = 0) const { return graph_.isEnabled(kind, subject); }
    bool isEnabled(const std::string& label) const { return graph_.isEnabled(label); }
    // Whether an enabled pass reads shadow `shadow`'s map.
    bool shadowUsed(size_t shadow) const;

    std::string describe() const { return graph_.describe(); }  // for --explain
    // With the time each pass took, by index (FrameScheduler), when known.
    nlohmann::json toJson(const std::vector<double>& passMilliseconds = {}) const;

private:
    FrameRecipe recipe_;
    FrameGraph graph_;
};

// What a frame asks of its plan besides the scene and the settings.
struct PlanRequest {
    // A host asked for primId/instanceId/elementId. Depth is always produced;
    // with blending, by the strand pass (NearestStrandRule.h).
    bool idsRequested = false;
    // The frame also delivers its display image, made on the GPU.
    bool displayOnGpu = false;
    // What earlier attempts at this frame found (FrameFallback.h).
    FrameFallbacks fallbacks;
    // The shadow maps' slots; without them the plan is provisional: it says
    // which maps are read (RenderPlan::shadowUsed), and draws none.
    std::optional<ShadowMapAssignment> shadowMaps;
};

// domes: the visible domes as the renderer fitted them (frameDomeEnvironments);
// a dome it does not list counts as untextured.
RenderPlan makeRenderPlan(const Scene& scene, const RenderSettings& settings, const CameraView& camera,
                          const StrandSummary& strands, const MeshSummary& meshes,
                          const std::vector<DomeEnvironment>& domes, const PlanRequest& request);
// The same, with a request of only the ids and the display image.
RenderPlan makeRenderPlan(const Scene& scene, const RenderSettings& settings, const CameraView& camera,
                          const StrandSummary& strands, bool idsRequested = false, const MeshSummary& meshes = {},
                          bool displayOnGpu = false, const std::vector<DomeEnvironment>& domes = {});

}  // namespace hdhair
