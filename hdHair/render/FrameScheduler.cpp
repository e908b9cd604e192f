#include "hdHair/render/FrameScheduler.h"

#include "hdHair/render/FrameResources.h"
#include "hdHair/render/RenderResult.h"

namespace hdhair {

void runFrameGraph(FrameContext& context, gl::PassTiming timing) {
    const std::vector<FramePass>& passes = context.plan.graph().passes();
    gl::PassTimer timer(timing, passes.size());
    for (size_t i = 0; i < passes.size(); ++i) {
        if (!passes[i].enabled) continue;
        if (stopRequested(context) && !runsWhenStopped(passes[i])) {
            if (std::optional<size_t> shadow = shadowMapBuiltBy(passes[i]))
                context.unbuiltShadowMaps.push_back(context.plan.recipe().shadows.lights[*shadow].key);
            continue;
        }
        timer.begin(i, isCpuPass(passes[i]));
        context.pass = &passes[i];
        runFramePass(passes[i], context);
        context.pass = nullptr;
        timer.end(i);
        if (context.cancellation) glFinish();
    }
    // What no pass of this frame used is not held for later ones.
    if (!context.plan.isEnabled(PassKind::DensityVolume)) context.resources.densityVolume.release();
    context.passMilliseconds = timer.collect();
    RenderStats& stats = context.result.stats;
    for (size_t i = 0; i < passes.size(); ++i)
        if (passes[i].enabled) stats.passes.push_back({passes[i].name, context.passMilliseconds[i]});
}

}  // namespace hdhair
