#pragma once
// Everything decided about a frame before any GL work, by one planner per
// concern: the lights and their batches (LightPlanner.h), the transparency
// path (TransparencyPlanner.h) and the shadows (ShadowPlanner.h). The frame
// graph is built from it (RenderPlan.h), and the passes execute with what it
// says: no pass reads a setting.

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "hdHair/render/DomeLighting.h"
#include "hdHair/render/LightPlanner.h"
#include "hdHair/render/SceneSummary.h"
#include "hdHair/render/ShadowPlanner.h"
#include "hdHair/render/TransparencyPlanner.h"
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

    // ShadowPlanner
    ShadowPlan shadows;

    // Each strand program compiled with only the shading its draw can reach
    // (specializeShaders), or with all of it.
    bool specializeShaders = true;
};

}  // namespace hdhair
