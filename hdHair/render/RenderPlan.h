#pragma once
// Which passes a frame runs, decided per scene before any GL work: only the
// effects a scene calls for are simulated, and what is off costs nothing.
// Each decision carries its reason, printed by --explain and kept in --stats.

#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "hdHair/shading/ShadingLight.h"

namespace hdhair {

class RenderSettings;
class Scene;
struct CameraView;

struct PlannedPass {
    std::string name;    // "strands"
    bool enabled = false;
    std::string reason;  // why it runs, or why not
};

struct RenderPlan {
    std::vector<PlannedPass> passes;
    ShadingLights lights;       // the stage's lights, plus the camera light when used
    bool cameraLight = false;

    bool isEnabled(const std::string& name) const;
    std::string describe() const;  // one line per pass, for --explain
    nlohmann::json toJson() const;
};

// segmentCount: segments of all visible prepared curves.
RenderPlan makeRenderPlan(const Scene& scene, const RenderSettings& settings, const CameraView& camera,
                          size_t segmentCount);

}  // namespace hdhair
