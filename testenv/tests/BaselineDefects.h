#pragma once
// The defects a baseline image must catch (the earlier rule passed
// renders with each of them). Which ones apply to a stage follows from what
// the stage contains, read from its scene, so a new stage gets its checks
// without anyone updating a list:
// - sorting off (transparency=unsorted: the sort pass skipped, strands
//   blended in authored order): where strands blend and two strands cover
//   the same pixels, since blending order shows nowhere else;
// - Kd 1 -> 0.9, Ks x 1.43, shininess 60 -> 30: where a visible prim is
//   shaded with Kajiya-Kay and does not author that parameter itself;
// - one complexity level lower: where a curve span bends or its width,
//   colour or opacity varies other than linearly, since tessellation shows
//   nowhere else (linear curves never qualify: their spans are straight
//   with linear widths and colours);
// - each light removed in turn: where the stage has lights and a lit prim.

#include <string>
#include <vector>

#include "StageRendering.h"
#include "hdHair/plan/CameraView.h"
#include "hdHair/plan/RenderPlan.h"
#include "hdHair/scene/Scene.h"

namespace hdhair::testenv {

struct BaselineDefect {
    std::string name;                   // for messages, e.g. "Kd 1 -> 0.9"
    std::vector<std::string> settings;  // NAME=VALUE added to the baseline's
    bool complexityOneLevelLower = false;
    std::string removedLight;           // a light's path, or ""
};

// `baselinePlan` is the plan the baseline render took (whether strands blend);
// `camera` the view it was rendered through.
std::vector<BaselineDefect> defectsThatApply(const Scene& scene, const StageRenderRequest& baseline,
                                             const RenderPlan& baselinePlan, const CameraView& camera);

// The baseline's scene and request with the defect applied.
struct DefectiveStage {
    Scene scene;
    StageRenderRequest request;
};
DefectiveStage withDefect(const Scene& scene, const StageRenderRequest& baseline, const BaselineDefect& defect);

}  // namespace hdhair::testenv
