#pragma once
// Everything decided about a frame before any GL work, by one planner per
// concern: the lights and their batches (LightPlanner.h), the transparency
// path (TransparencyPlanner.h), who rasterises the strands
// (StrandRasterPlanner.h) and the shadows (ShadowPlanner.h). The frame
// graph is built from it (RenderPlan.h), and the passes execute with what it
// says: no pass reads a setting.

#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "hdHair/plan/DomeLighting.h"
#include "hdHair/plan/LightPlanner.h"
#include "hdHair/plan/SceneSummary.h"
#include "hdHair/plan/ShadowPlanner.h"
#include "hdHair/plan/StrandRasterPlanner.h"
#include "hdHair/plan/TransparencyPlanner.h"
#include "hdHair/shading/ShadingLight.h"

namespace hdhair {

struct FrameRecipe {
    // LightPlanner
    ShadingLights lights;       // the stage's lights, plus the camera light when used
    bool cameraLight = false;
    bool flatShading = false;   // every prim flat: no lights needed
    bool meshesLit = false;     // meshes shaded with the lights (Lambert), else displayColor unlit
    // Light passes: [begin, end) ranges of `lights.lights`, at most
    // lightsPerPass each; always at least one (ambient and unlit shading
    // need a pass too).
    std::vector<std::pair<size_t, size_t>> lightBatches;
    // The domes as domeLighting=srbf shades them (empty with ambient).
    std::vector<PlannedDome> domes;
    // Stage lights beyond kMaxLights, left out of the frame.
    size_t lightsOverCap = 0;

    // TransparencyPlanner
    TransparencyPath transparency = TransparencyPath::Opaque;
    std::string transparencyReason;  // why this path, for --explain
    uint32_t sortBins = 0;      // for BinSorted
    int msaaSamples = 0;        // for Opaque
    // Exact transparency's fragment budget (exactMemoryMB), and whether a
    // frame over it fails (exactOverflow=fail) rather than fall back.
    int exactMemoryMB = 512;
    bool exactOverflowFails = false;

    // StrandRasterPlanner: the compute rasteriser's fragment lists are
    // bounded by strandRasterMemoryMB; a frame over it warns and is drawn by
    // the hardware path.
    StrandRaster strandRaster = StrandRaster::Hardware;
    std::string strandRasterReason;
    int strandRasterMemoryMB = 512;
    // With the compute rasteriser, per drawn prim (draw order): whether the
    // hardware rasteriser lists its fragments instead, into the same
    // per-pixel lists (strandRaster=auto's prims too wide for compute).
    // Empty: compute lists every prim.
    std::vector<bool> listedByHardware;
    // About how many fragments the frame's lists will hold (each prim's
    // segments times the pixels StrandSummary estimates a span of it
    // covers), so that a first frame sizes its list storage once rather
    // than render again into storage of the size it counted; 0 when unknown
    // (bounds reaching the camera, or no per-prim figures).
    uint64_t expectedFragments = 0;
    bool mixesRasterisers() const {
        return strandRaster == StrandRaster::Compute &&
               std::find(listedByHardware.begin(), listedByHardware.end(), true) != listedByHardware.end();
    }

    // ShadowPlanner
    ShadowPlan shadows;

    // Whether the strands are composited from per-pixel lists (exact
    // transparency, or the compute rasteriser), whose resolve gives the
    // frame its depth and ids.
    bool compositesFromLists() const {
        return transparency == TransparencyPath::Exact || strandRaster == StrandRaster::Compute;
    }
    // Whether the strands are drawn in the bin sort's order.
    bool drawsSorted() const {
        return transparency == TransparencyPath::BinSorted && strandRaster == StrandRaster::Hardware;
    }

    // Each strand program compiled with only the shading its draw can reach
    // (specializeShaders), or with all of it.
    bool specializeShaders = true;
};

}  // namespace hdhair
