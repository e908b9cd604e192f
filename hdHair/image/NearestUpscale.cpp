#include "hdHair/image/NearestUpscale.h"

#include <algorithm>
#include <stdexcept>

namespace hdhair {

namespace {

// The source pixel a result pixel repeats, in one dimension.
int sourceOf(int x, int from, int to) { return std::min(from - 1, int(int64_t(x) * from / to)); }

}  // namespace

Image upscaleNearest(const Image& image, int width, int height) {
    if (image.width <= 0 || image.height <= 0 || image.pixels.size() != size_t(image.width) * size_t(image.height) * size_t(image.channels))
        throw std::invalid_argument("upscaleNearest: the image has no pixels or not as many as its size says");
    Image result(width, height, image.channels);
    for (int y = 0; y < height; ++y) {
        const int sy = sourceOf(y, image.height, height);
        for (int x = 0; x < width; ++x) {
            const int sx = sourceOf(x, image.width, width);
            for (int c = 0; c < image.channels; ++c) result.at(x, y, c) = image.at(sx, sy, c);
        }
    }
    return result;
}

std::vector<int32_t> upscaleNearest(const std::vector<int32_t>& values, int fromWidth, int fromHeight, int width,
                                    int height) {
    if (fromWidth <= 0 || fromHeight <= 0 || values.size() != size_t(fromWidth) * size_t(fromHeight))
        throw std::invalid_argument("upscaleNearest: the values are not a fromWidth x fromHeight image");
    std::vector<int32_t> result(size_t(width) * size_t(height));
    for (int y = 0; y < height; ++y) {
        const int sy = sourceOf(y, fromHeight, height);
        for (int x = 0; x < width; ++x)
            result[size_t(y) * size_t(width) + size_t(x)] =
                values[size_t(sy) * size_t(fromWidth) + size_t(sourceOf(x, fromWidth, width))];
    }
    return result;
}

}  // namespace hdhair
