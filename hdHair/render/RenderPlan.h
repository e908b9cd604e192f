#pragma once
// Which passes a frame runs, decided per scene before any GL work: only the
// effects a scene calls for are simulated, and what is off costs nothing.
// Each decision carries its reason, printed by --explain and kept in --stats.

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

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

struct PlannedPass {
    std::string name;    // "strands"
    bool enabled = false;
    std::string reason;  // why it runs, or why not
};

struct RenderPlan {
    std::vector<PlannedPass> passes;
    ShadingLights lights;       // the stage's lights, plus the camera light when used
    bool cameraLight = false;
    TransparencyPath transparency = TransparencyPath::Opaque;
    uint32_t sortBins = 0;      // for BinSorted
    int msaaSamples = 0;        // for Opaque
    bool flatShading = false;   // every prim flat: no lights needed
    // Light passes: [begin, end) ranges of `lights.lights`, at most
    // lightsPerPass each; always at least one (ambient and unlit shading
    // need a pass too).
    std::vector<std::pair<size_t, size_t>> lightBatches;

    bool isEnabled(const std::string& name) const;
    // Exact transparency over its memory budget: the frame is redrawn
    // binSorted with `bins` bins, which needs the ids pass when ids are asked for.
    void fallBackToBinSorted(uint32_t bins, bool idsRequested);
    std::string describe() const;  // one line per pass, for --explain
    nlohmann::json toJson() const;
};

// idsRequested: a host asked for primId/instanceId/elementId. Depth is always
// produced; with blending, by the strand pass (NearestStrandRule.h).
RenderPlan makeRenderPlan(const Scene& scene, const RenderSettings& settings, const CameraView& camera,
                          const StrandSummary& strands, bool idsRequested = false);

}  // namespace hdhair
