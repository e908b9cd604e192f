#pragma once
// How a frame may be stopped or simplified: what ProgressiveRenderer and the
// interactive previews hand to Renderer::render.

#include <cstddef>

namespace hdhair {

class FrameCancellation;

// Segments per piece of a cancellable frame's strand draws (FramePasses.h):
// a request to stop waits for at most one piece, and every piece costs a
// finish of the GL work; docs/hydra-plugin.md ("Progressive rendering") has what 2,048 gives on
// the dense clump (27,900 segments: 14 pieces a draw).
constexpr size_t kStrandPieceSegments = 2048;

struct FrameControl {
    // Asked between passes and between strand pieces whether to stop
    // (FrameCancellation.h); a stopped frame throws FrameCancelled. Null:
    // the frame runs to its end and draws its strands at once.
    const FrameCancellation* cancellation = nullptr;
    size_t strandPieceSegments = kStrandPieceSegments;
    // A preview (InteractivePreview.h): its settings and image size are not
    // those of the frames before and after it, so it keeps the shadow maps
    // as the last full frame left them (building and dropping none: its
    // settings must have shadowMode=off).
    bool preview = false;
    // A preview draws every this-many-th curve of each prim only
    // (keepEveryNthCurve, InteractivePreview.h); 1 for every other frame.
    int previewCurveStride = 1;
    // Whether each pass's code is checked against the resources its pass
    // declares (FramePasses.cpp: a pass touching one it did not declare
    // throws std::logic_error): in debug builds always, and where a test
    // asks for it.
#ifdef NDEBUG
    bool checkResourceAccess = false;
#else
    bool checkResourceAccess = true;
#endif
};

}  // namespace hdhair
