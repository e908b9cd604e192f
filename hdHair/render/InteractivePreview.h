#pragma once
// The preview an interactive host shows while its view changes, in place of
// a full frame that takes longer than interactiveBudgetMs
// (ProgressiveRenderer.h decides when). A preview is the same scene and
// camera drawn cheaply:
//  - coarse tessellation: tessellationTolerance at least 1 pixel (or, under
//    projectedLength, pixelsPerSegment at least 16), at most 4 segments a
//    span;
//  - binSorted with at most 16 bins (exact transparency too; unsorted and
//    the opaque path stay as they are);
//  - no shadows (shadowMode=off): the full frames' shadow maps are left as
//    they are (FrameControl::preview);
//  - every light in one pass (lightsPerPass=16), no multisampling or
//    supersampling,
//    Marschner from its tables, no pass timings;
//  - and, when that alone is over the budget (PreviewBudget), fewer pixels,
//    1/2, 1/4 or 1/8 of them across, enlarged to the host's size by
//    repeating pixels (NearestUpscale.h); then, at 1/8, every 2nd, 4th, 8th
//    or 16th curve of each prim only, the same curves in every preview so
//    that a moving view does not flicker between them.
// Hair on llvmpipe costs fragments, and strands thinner than a pixel are
// drawn a pixel wide (minPixelWidth): a quarter of the width costs about a
// quarter, not a sixteenth, and the dense clump at 1/8 of 960 pixels is still
// over 100 ms (docs/hydra-plugin.md: measured), hence the curves. Fewer
// curves cover less: the strand shader keeps each strand's coverage to its
// own width, so a thinned preview looks sparser and lighter than the frame.

#include "hdHair/plan/CameraView.h"
#include "hdHair/plan/RenderSettings.h"

namespace hdhair {

struct FrameInputs;
struct RenderResult;

// A full frame's settings made into its preview's (above).
RenderSettings previewSettings(const RenderSettings& full);

// The camera of a preview with 1/divisor of the full camera's pixels across
// and down (at least one): the same view and projection.
CameraView previewCamera(const CameraView& full, int divisor);

// A preview's images enlarged to the full camera's size (colour, depth and
// the ids it has).
void enlargePreview(RenderResult& preview, int width, int height);

// Keeps every `stride`-th curve (by its index in its prim) of each drawn
// prim in a frame's draws: its sort spans and draw ranges. The uploads are
// left whole: the GPU keeps every strand.
void keepEveryNthCurve(FrameInputs& inputs, int stride);

// How far the next preview is cut down, from how long the last one took.
// Level 0 is the full width; each level above roughly halves the cost:
// levels 1 to 3 halve the pixels across (1/2, 1/4, 1/8), levels 4 to 7 then
// halve the curves (every 2nd, 4th, 8th, 16th). A preview over the budget by
// a factor r moves ceil(log2 r) levels up; one under a third of it moves a
// level down. Before any preview, the first is placed from the full frame's
// time the same way (a preview costs less than its full frame, so it starts
// at most a level too low and comes back down as previews come in quick).
class PreviewBudget {
public:
    static constexpr int kTopLevel = 7;

    int level() const { return level_; }
    int pixelDivisor() const;  // 1, 2, 4 or 8
    int curveStride() const;   // 1, 2, 4, 8 or 16

    void recordPreview(double milliseconds, double budgetMilliseconds);
    // The full frame's time, which places the first preview.
    void recordFullFrame(double milliseconds, double budgetMilliseconds);

private:
    void moveBy(double milliseconds, double budgetMilliseconds);
    int level_ = 0;
    bool previewed_ = false;
};

}  // namespace hdhair
