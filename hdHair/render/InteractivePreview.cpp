#include "hdHair/render/InteractivePreview.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "hdHair/image/NearestUpscale.h"
#include "hdHair/render/Renderer.h"

namespace hdhair {

RenderSettings previewSettings(const RenderSettings& full) {
    RenderSettings preview = full;
    preview.set("pixelsPerSegment", std::to_string(std::max(full.getFloat("pixelsPerSegment"), 16.0)));
    preview.set("maxSegmentsPerSpan", std::to_string(std::min(full.getInt("maxSegmentsPerSpan"), 4)));
    if (full.getToken("transparency") == "exact") preview.set("transparency", "binSorted");
    preview.set("sortBins", std::to_string(std::min(full.getInt("sortBins"), 16)));
    preview.set("shadowMode", "off");
    preview.set("lightsPerPass", "16");
    preview.set("msaaSamples", "0");
    if (full.getToken("marschner:azimuthal") == "analytic") preview.set("marschner:azimuthal", "tables");
    preview.set("passTimings", "false");
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

void PreviewBudget::record(double milliseconds, double budgetMilliseconds) {
    if (budgetMilliseconds <= 0.0) return;
    if (milliseconds > budgetMilliseconds) {
        const int steps = int(std::ceil(std::log2(milliseconds / budgetMilliseconds)));
        for (int step = 0; step < steps && divisor_ < kMaxDivisor; ++step) divisor_ *= 2;
    } else if (milliseconds < budgetMilliseconds / 3.0 && divisor_ > 1) {
        divisor_ /= 2;
    }
}

}  // namespace hdhair
