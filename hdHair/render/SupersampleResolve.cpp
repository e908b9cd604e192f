#include "hdHair/render/SupersampleResolve.h"

#include <stdexcept>

#include <fmt/format.h>

#include "hdHair/image/BoxDownsample.h"
#include "hdHair/render/RenderResult.h"

namespace hdhair {

namespace {

constexpr int kLargestTarget = 16384;

}  // namespace

CameraView supersampledCamera(const CameraView& camera, int factor) {
    if (factor < 1) throw std::invalid_argument(fmt::format("supersampling must be at least 1, got {}", factor));
    if (int64_t(camera.imageWidth) * factor > kLargestTarget || int64_t(camera.imageHeight) * factor > kLargestTarget)
        throw std::invalid_argument(fmt::format("supersampling={} needs a {}x{} frame, larger than {} pixels across",
                                                factor, int64_t(camera.imageWidth) * factor,
                                                int64_t(camera.imageHeight) * factor, kLargestTarget));
    CameraView fine = camera;
    fine.imageWidth = camera.imageWidth * factor;
    fine.imageHeight = camera.imageHeight * factor;
    return fine;
}

void resolveSupersampling(RenderResult& result, int factor) {
    if (factor == 1) return;
    const bool ids = !result.primIds.empty();
    if (ids && result.depth.pixels.empty())
        throw std::logic_error("resolveSupersampling needs the depth image to choose the ids");
    const int fineWidth = result.color.width;
    result.color = boxDownsample(result.color, factor);
    if (result.depth.pixels.empty()) return;
    const int width = result.color.width, height = result.color.height;
    Image depth(width, height, 1);
    std::vector<int32_t> primIds, instanceIds, elementIds;
    if (ids) {
        primIds.resize(size_t(width) * size_t(height));
        instanceIds.resize(primIds.size());
        elementIds.resize(primIds.size());
    }
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            int nearestX = x * factor, nearestY = y * factor;
            for (int sy = y * factor; sy < (y + 1) * factor; ++sy)
                for (int sx = x * factor; sx < (x + 1) * factor; ++sx)
                    if (result.depth.at(sx, sy, 0) < result.depth.at(nearestX, nearestY, 0)) {
                        nearestX = sx;
                        nearestY = sy;
                    }
            depth.at(x, y, 0) = result.depth.at(nearestX, nearestY, 0);
            if (!ids) continue;
            const size_t sample = size_t(nearestY) * size_t(fineWidth) + size_t(nearestX);
            const size_t pixel = size_t(y) * size_t(width) + size_t(x);
            primIds[pixel] = result.primIds[sample];
            instanceIds[pixel] = result.instanceIds[sample];
            elementIds[pixel] = result.elementIds[sample];
        }
    result.depth = std::move(depth);
    if (ids) {
        result.primIds = std::move(primIds);
        result.instanceIds = std::move(instanceIds);
        result.elementIds = std::move(elementIds);
    }
}

}  // namespace hdhair
