#include "hdHair/render/FrameScheduler.h"

#include "hdHair/render/RenderResult.h"

namespace hdhair {

void runFrameGraph(FrameContext& context, gl::PassTiming timing) {
    std::vector<FramePass>& passes = context.plan.graph.passes();
    gl::PassTimer timer(timing, passes.size());
    for (size_t i = 0; i < passes.size(); ++i) {
        if (!passes[i].enabled) continue;
        if (stopRequested(context) && !runsWhenStopped(passes[i])) {
            if (std::optional<size_t> shadow = shadowMapBuiltBy(passes[i]))
                context.unbuiltShadowMaps.push_back(context.plan.shadows.lights[*shadow].key);
            continue;
        }
        timer.begin(i, isCpuPass(passes[i]));
        runFramePass(passes[i], context);
        timer.end(i);
        if (context.cancellation) glFinish();
    }
    const std::vector<double> milliseconds = timer.collect();
    RenderStats& stats = context.result.stats;
    for (size_t i = 0; i < passes.size(); ++i) {
        if (!passes[i].enabled) continue;
        passes[i].milliseconds = milliseconds[i];
        stats.passes.push_back({passes[i].name, milliseconds[i]});
    }
}

}  // namespace hdhair
