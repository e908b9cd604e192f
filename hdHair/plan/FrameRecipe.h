#pragma once
// Everything decided about a frame before any GL work, by one planner per
// concern, each returning its own plan. A planner takes the plans it depends
// on as parameters, so their order is in the types:
//   planLights (LightPlanner.h)              the lights, the domes as lights, the camera light, their batches
//   planShadows(lights)  (ShadowPlanner.h)   which lights cast shadows and how their maps are drawn
//   planTransparency (TransparencyPlanner.h) how the strands are composited
//   planStrandRaster(transparency)           who rasterises them (StrandRasterPlanner.h)
//   planTessellation(transparency)           how they are cut and widened (TessellationPlanner.h)
//   planExecution (ExecutionPlan.h)          batching, timing, shader specialisation
// The frame graph is built from the recipe (RenderPlan.h), and the passes
// execute with what it says: no pass reads a setting.

#include <optional>
#include <vector>

#include "hdHair/plan/ExecutionPlan.h"
#include "hdHair/plan/FrameFallback.h"
#include "hdHair/plan/LightPlanner.h"
#include "hdHair/plan/SceneSummary.h"
#include "hdHair/plan/ShadowPlanner.h"
#include "hdHair/plan/StrandRasterPlanner.h"
#include "hdHair/plan/TessellationPlanner.h"
#include "hdHair/plan/TransparencyPlanner.h"

namespace hdhair {

class RenderSettings;

struct FrameRecipe {
    LightPlan lighting;
    ShadowPlan shadows;
    TransparencyPlan transparency;
    StrandRasterPlan strandRaster;
    TessellationPlan tessellation;
    ExecutionPlan execution;

    // Whether the strands are composited from per-pixel lists (exact
    // transparency, or the compute rasteriser), whose resolve gives the
    // frame its depth and ids.
    bool compositesFromLists() const {
        return transparency.path == TransparencyPath::Exact || strandRaster.rasteriser == StrandRaster::Compute;
    }
    // Whether the strands are drawn in the bin sort's order.
    bool drawsSorted() const {
        return transparency.path == TransparencyPath::BinSorted && strandRaster.rasteriser == StrandRaster::Hardware;
    }
};

// The recipe of a frame: every planner, in the order their types give.
// fallbacks: what earlier attempts at the frame found (FrameFallback.h);
// shadowMaps: the renderer's decision for each map, or none (provisional).
FrameRecipe makeFrameRecipe(const Scene& scene, const RenderSettings& settings, const CameraView& camera,
                            const StrandSummary& strands, const MeshSummary& meshes,
                            const std::vector<DomeEnvironment>& domes, const FrameFallbacks& fallbacks,
                            const std::optional<ShadowMapAssignment>& shadowMaps);

}  // namespace hdhair
