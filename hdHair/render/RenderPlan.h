#pragma once
// Which passes a frame runs, decided per scene before any GL work: only the
// effects a scene calls for are simulated, and what is off costs nothing.
// The planners decide the frame's recipe (FrameRecipe.h); the plan is that
// recipe with the FrameGraph built from it (FrameGraph.h): each pass with its
// kind, what it reads and writes and the reason it runs or not, printed by
// --explain and kept, with each pass's time, in --stats.

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "hdHair/render/FrameGraph.h"
#include "hdHair/render/FrameRecipe.h"

namespace hdhair {

struct CameraView;

// The passes, in the order they run:
//   upload        preparedStrands -> strands        GPU copy of the changed prims
//   meshUpload    preparedMeshes -> meshGeometry    GPU copy of the meshes, when one changed
//   sort          preparedStrands -> drawOrder      binSorted only, by the hardware rasteriser
//   shadowDepth L      strands -> hairDepth L       per shadow-casting light L: its nearest hair
//   deepOpacity L      strands, hairDepth L -> deepOpacity L   its opacity layers
//   shadowFragments L  strands -> shadowFragments L  shadowMode=reference instead: every fragment
//   meshShadow L       meshGeometry -> meshDepth L  with meshes: the nearest mesh, which hides the hair behind it
//                 (a map kept from an earlier frame is an input of the graph instead)
//   clear         -> color, depth[, ids]            the frame's targets, empty
//   meshes        meshGeometry, color, depth[, ids] -> color, depth[, ids]   opaque, lights of batch 1
//   strands       strands[, drawOrder], color, depth[, the batch's shadows] -> color, depth[, ids]   lights of batch 1
//   ids           strands, depth -> ids             blended paths, when a host asks for ids
//   resolve       color, depth[, ids] (in place)    multisampled frames
//   lightBatch k  [strands[, drawOrder],] [meshGeometry,] color[, the batch's shadows] -> color   lights of batch k (k >= 2)
//   readback      color, depth[, ids] -> aovs       the frame's images, to the CPU
//   displayTransform  color -> displayImage         the display image on the GPU, when asked for
// Meshes are drawn first and write depth, so every strand path tests
// against them (NearestStrandRule.h: how their depth and ids combine with
// the strands').
struct RenderPlan : FrameRecipe {
    FrameGraph graph;

    bool isEnabled(PassKind kind, size_t subject = 0) const { return graph.isEnabled(kind, subject); }
    bool isEnabled(const std::string& label) const { return graph.isEnabled(label); }
    // Exact transparency over its memory budget: the frame is redrawn
    // binSorted with `bins` bins, which needs the ids pass when ids are asked for.
    void fallBackToBinSorted(uint32_t bins, bool idsRequested);
    // The compute rasteriser over its memory budget: the frame is redrawn
    // by the hardware path with the transparency planned (binSorted needs
    // the sort, and the ids pass when ids are asked for).
    void fallBackToHardwareRaster(bool idsRequested);
    // The renderer's decision for shadow `shadow` (ShadowMapCache): rebuilt
    // by its passes, or kept, when its map becomes an input of the graph and
    // its passes do not run.
    void setShadowMap(size_t shadow, int slot, bool rebuild, const std::string& reason);
    // Whether an enabled pass reads shadow `shadow`'s map.
    bool shadowUsed(size_t shadow) const;
private:
    // The sort, ids and strand passes again for the hardware path with the
    // recipe's transparency.
    void redrawStrandsWithHardware(const std::string& sortReason, bool idsRequested);

public:
    std::string describe() const { return graph.describe(); }  // for --explain
    nlohmann::json toJson() const;
};

// idsRequested: a host asked for primId/instanceId/elementId. Depth is always
// produced; with blending, by the strand pass (NearestStrandRule.h).
// displayOnGpu: the frame also delivers its display image, made on the GPU.
// domes: the visible domes as the renderer fitted them (frameDomeEnvironments);
// a dome it does not list counts as untextured.
RenderPlan makeRenderPlan(const Scene& scene, const RenderSettings& settings, const CameraView& camera,
                          const StrandSummary& strands, bool idsRequested = false, const MeshSummary& meshes = {},
                          bool displayOnGpu = false, const std::vector<DomeEnvironment>& domes = {});

}  // namespace hdhair
