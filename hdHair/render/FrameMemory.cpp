#include "hdHair/render/FrameMemory.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>


namespace hdhair {

uint64_t frameImageBytes(int width, int height, int msaaSamples, bool ids, bool depth) {
    const uint64_t samples = uint64_t(std::max(msaaSamples, 1));
    // GL: colour (16) and depth (4) per sample, ids (3 x 4) and the nearest
    // depth (4) when asked, a resolved copy when multisampled, and the light
    // batches' colour and depth.
    const uint64_t targetBytes = 20 + (ids ? 16 : 0);
    uint64_t perPixel = targetBytes * samples + (msaaSamples > 0 ? targetBytes : 0) + 20 * samples;
    // CPU: the colour read back (16), the display image (4) and the image
    // writer's copy of the colour (16), depth (4) and ids (12) when asked.
    perPixel += 36 + (depth ? 4 : 0) + (ids ? 12 : 0);
    return perPixel * uint64_t(std::max(width, 0)) * uint64_t(std::max(height, 0));
}

void checkFrameFitsMemory(int width, int height, const RenderSettings& settings, bool ids, bool depth,
                          uint64_t hostBytesPerPixel, const AvailableMemory& available) {
    const uint64_t pixels = uint64_t(std::max(width, 1)) * uint64_t(std::max(height, 1));
    const uint64_t needed =
        frameImageBytes(width, height, settings.values().msaaSamples, ids, depth) + hostBytesPerPixel * pixels;
    if (needed <= available.bytes) return;
    // The same shape, scaled down by the square root of the shortfall.
    const double scale = std::sqrt(double(available.bytes) / double(needed));
    const int widest = std::max(0, int(std::floor(width * scale)));
    throw std::runtime_error(fmt::format(
        "a {}x{} frame needs about {} for its images ({} bytes a pixel), more than the {} this process can take "
        "({}); at this shape at most {} pixels wide fits: lower the image width",
        width, height, describeBytes(needed), needed / pixels, describeBytes(available.bytes), available.limitedBy,
        widest));
}

}  // namespace hdhair
