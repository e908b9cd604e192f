#include "hdHair/render/InteractivePreview.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "hdHair/image/NearestUpscale.h"
#include "hdHair/render/FramePasses.h"
#include "hdHair/render/RenderResult.h"

namespace hdhair {

RenderSettings previewSettings(const RenderSettings& full) {
    RenderSettings preview = full;
    const SettingValues& values = full.values();
    preview.setValue(&SettingValues::tessellationTolerance, std::max(values.tessellationTolerance, 1.0));
    preview.setValue(&SettingValues::pixelsPerSegment, std::max(values.pixelsPerSegment, 16.0));
    preview.setValue(&SettingValues::maxSegmentsPerSpan, std::min(values.maxSegmentsPerSpan, 4));
    if (values.transparency == TransparencyPath::Exact)
        preview.setValue(&SettingValues::transparency, TransparencyPath::BinSorted);
    preview.setValue(&SettingValues::sortBins, std::min(values.sortBins, 16));
    preview.setValue(&SettingValues::shadowMode, ShadowMode::Off);
    preview.setValue(&SettingValues::lightsPerPass, 16);
    preview.setValue(&SettingValues::msaaSamples, 0);
    preview.setValue(&SettingValues::supersampling, 1);
    if (values.marschnerAzimuthal == MarschnerAzimuthal::Analytic)
        preview.setValue(&SettingValues::marschnerAzimuthal, MarschnerAzimuthal::Tables);
    preview.setValue(&SettingValues::passTimings, false);
    return preview;
}

CameraView previewCamera(const CameraView& full, int divisor) {
    CameraView camera = full;
    camera.imageWidth = std::max(1, full.imageWidth / divisor);
    camera.imageHeight = std::max(1, full.imageHeight / divisor);
    return camera;
}

void enlargePreview(RenderResult& preview, int width, int height) {
    const int fromWidth = preview.color.width, fromHeight = preview.color.height;
    if (fromWidth == width && fromHeight == height) return;
    preview.color = upscaleNearest(preview.color, width, height);
    preview.depth = upscaleNearest(preview.depth, width, height);
    for (std::vector<int32_t>* ids : {&preview.primIds, &preview.instanceIds, &preview.elementIds})
        if (!ids->empty()) *ids = upscaleNearest(*ids, fromWidth, fromHeight, width, height);
}

void keepEveryNthCurve(FrameInputs& inputs, int stride) {
    if (stride <= 1) return;
    std::vector<SortSpan> spans;
    std::vector<gl::SegmentRange> ranges;
    for (size_t prim = 0; prim < inputs.drawn.size(); ++prim) {
        const std::vector<uint32_t>& segmentCurve = inputs.drawn[prim].curves->segmentCurve;
        const SortSpan& whole = inputs.sortSpans[prim];
        // A curve's segments are consecutive: kept curves make runs.
        for (size_t first = 0; first < segmentCurve.size();) {
            if (segmentCurve[first] % uint32_t(stride) != 0) {
                ++first;
                continue;
            }
            size_t end = first;
            while (end < segmentCurve.size() && segmentCurve[end] % uint32_t(stride) == 0) ++end;
            spans.push_back(SortSpan{whole.controlPoints, whole.firstControl + first, whole.hashes + first, end - first,
                                     whole.first + first});
            const gl::SegmentRange run{whole.first + first, end - first};
            if (!ranges.empty() && ranges.back().first + ranges.back().count == run.first)
                ranges.back().count += run.count;
            else
                ranges.push_back(run);
            first = end;
        }
    }
    inputs.sortSpans = std::move(spans);
    inputs.uploads.drawRanges = std::move(ranges);
}

int PreviewBudget::pixelDivisor() const { return 1 << std::min(level_, 3); }

int PreviewBudget::curveStride() const { return 1 << std::max(level_ - 3, 0); }

void PreviewBudget::recordPreview(double milliseconds, double budgetMilliseconds) {
    previewed_ = true;
    moveBy(milliseconds, budgetMilliseconds);
}

void PreviewBudget::recordFullFrame(double milliseconds, double budgetMilliseconds) {
    if (previewed_) return;
    level_ = 0;
    moveBy(milliseconds, budgetMilliseconds);
}

void PreviewBudget::moveBy(double milliseconds, double budgetMilliseconds) {
    if (budgetMilliseconds <= 0.0) return;
    if (milliseconds > budgetMilliseconds)
        level_ = std::min(kTopLevel, level_ + int(std::ceil(std::log2(milliseconds / budgetMilliseconds))));
    else if (milliseconds < budgetMilliseconds / 3.0)
        level_ = std::max(0, level_ - 1);
}

}  // namespace hdhair
