#pragma once
// How a frame's passes run, apart from what they draw: the settings that
// change what a frame costs or reports, never its picture.

#include "hdHair/plan/SettingTokens.h"
#include "hdHair/plan/SettingValues.h"

namespace hdhair {

struct ExecutionPlan {
    // Whether the strand draws are batched (drawBatching; auto: the
    // renderer asks the GL driver, gl::PatchBatching::forDriver).
    DrawBatching batching = DrawBatching::Auto;
    // Each pass timed for --stats (passTimings).
    bool passTimings = false;
    // Each strand program compiled with only the shading its draw can reach
    // (specializeShaders), or with all of it.
    bool specializeShaders = true;
};

inline ExecutionPlan planExecution(const SettingValues& settings) {
    return {settings.drawBatching, settings.passTimings, settings.specializeShaders};
}

}  // namespace hdhair
