#pragma once
// Runs a frame's compiled graph (RenderPlan.h) on the GL thread: every
// enabled pass in order through runFramePass(), each timed when timing is
// on (gl::PassTimer), its milliseconds kept on the graph. A pass may change
// the plan as it runs (exact transparency falling back to bin sorting
// enables the ids pass); the scheduler reads each pass's state as it comes
// to it.

#include "hdHair/gl/PassTimer.h"
#include "hdHair/render/FramePasses.h"

namespace hdhair {

void runFrameGraph(FrameContext& context, gl::PassTiming timing);

}  // namespace hdhair
