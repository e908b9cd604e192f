#pragma once
// Runs a frame's compiled graph (RenderPlan.h) on the GL thread: every
// enabled pass in order through runFramePass(), each timed when timing is
// on (gl::PassTimer), its milliseconds kept in the context
// (FrameContext::passMilliseconds), never on the plan, which no pass
// changes. A pass that finds the plan impossible (FrameFallback.h) reports
// it and stops the frame as a cancellation does; the Renderer plans again.
//
// A frame that can be cancelled (FrameContext::cancellation) finishes each
// pass's GL work before the next (llvmpipe would otherwise do it all at the
// readback, past every chance to stop) and asks before each pass whether to
// stop; once stopped, it runs only the passes runsWhenStopped() names and
// records the shadow maps it left unbuilt.

#include "hdHair/gl/PassTimer.h"
#include "hdHair/render/FramePasses.h"

namespace hdhair {

void runFrameGraph(FrameContext& context, gl::PassTiming timing);

}  // namespace hdhair
