#pragma once
// What a frame delivers (Renderer::render): the images, and the plan and
// statistics that say how they were made.

#include <cstdint>
#include <string>
#include <vector>

#include "hdHair/image/Image.h"
#include "hdHair/plan/RenderPlan.h"
#include "hdHair/render/RenderStats.h"

namespace hdhair {

// A plan a frame made and gave up (FrameFallback.h): why, and the plan as it
// ran until a pass found it impossible, with its passes' times.
struct AbandonedPlan {
    std::string reason;
    RenderPlan plan;
    std::vector<double> passMilliseconds;
};

struct RenderResult {
    Image color;  // RGBA, scene-linear, pre-multiplied
    // One channel, window depth in [0, 1], 1 where empty (empty itself when
    // RenderOutputs::depth is off). Blended frames: the
    // depth of the nearest fragment of alpha >= kNearestStrandMinAlpha
    // (NearestStrandRule.h), whether or not ids are asked for.
    Image depth;
    // With RenderOutputs::ids: per pixel, rows from the top down; -1 where
    // empty. The same fragment as depth, on every path.
    std::vector<int32_t> primIds, instanceIds, elementIds;
    // With RenderOutputs::gpuDisplay: RGBA display code values, rows from the top down.
    Image display;
    RenderPlan plan;  // the plan the images come from
    std::vector<AbandonedPlan> abandonedPlans;  // the plans made before it, in order
    RenderStats stats;

    // --explain: every plan the frame made, the abandoned ones first with why.
    std::string describePlans() const {
        std::string text;
        for (const AbandonedPlan& abandoned : abandonedPlans)
            text += abandoned.plan.describe() + "  (this plan was abandoned: " + abandoned.reason +
                    "; the frame was planned again)\n";
        return text + plan.describe();
    }
};

}  // namespace hdhair
