#pragma once
// What a frame delivers (Renderer::render): the images, and the plan and
// statistics that say how they were made.

#include <cstdint>
#include <vector>

#include "hdHair/image/Image.h"
#include "hdHair/render/RenderPlan.h"
#include "hdHair/render/RenderStats.h"

namespace hdhair {

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
    RenderPlan plan;
    RenderStats stats;
};

}  // namespace hdhair
