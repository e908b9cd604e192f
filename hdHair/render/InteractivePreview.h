#pragma once
// The preview an interactive host shows while its view changes, in place of
// a full frame that takes longer than interactiveBudgetMs
// (ProgressiveRenderer.h decides when). A preview is the same scene and
// camera drawn cheaply:
//  - coarse tessellation: pixelsPerSegment at least 16, at most 4 segments
//    a span (spans stay curved, with a quarter of the default's vertices);
//  - binSorted with at most 16 bins (exact transparency too; unsorted and
//    the opaque path stay as they are);
//  - no shadows (shadowMode=off): the full frames' shadow maps are left as
//    they are (FrameControl::preview);
//  - every light in one pass (lightsPerPass=16), no multisampling,
//    Marschner from its tables, no pass timings;
//  - and, when that alone is over the budget, fewer pixels: 1/2, 1/4 or 1/8
//    of them across (PreviewBudget), enlarged to the host's size by
//    repeating pixels (NearestUpscale.h).
// Hair on llvmpipe costs fragments: strands thinner than a pixel are drawn
// a pixel wide (minPixelWidth), so a quarter of the width costs about a
// quarter, not a sixteenth (README, "Hydra plugin": measured).

#include "hdHair/render/CameraView.h"
#include "hdHair/render/RenderSettings.h"

namespace hdhair {

struct RenderResult;

// A full frame's settings made into its preview's (above).
RenderSettings previewSettings(const RenderSettings& full);

// The camera of a preview with 1/divisor of the full camera's pixels across
// and down (at least one): the same view and projection.
CameraView previewCamera(const CameraView& full, int divisor);

// A preview's images enlarged to the full camera's size (colour, depth and
// the ids it has).
void enlargePreview(RenderResult& preview, int width, int height);

// Chooses how many times fewer pixels across the next preview has, from how
// long the last one took: each halving of the width roughly halves the cost
// (above), so a preview over the budget by a factor r moves ceil(log2 r)
// steps down (at most to 1/8), and one under a third of the budget moves a
// step back up. Starts at full width.
class PreviewBudget {
public:
    static constexpr int kMaxDivisor = 8;

    int divisor() const { return divisor_; }
    void record(double milliseconds, double budgetMilliseconds);

private:
    int divisor_ = 1;
};

}  // namespace hdhair
