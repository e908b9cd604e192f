#pragma once
// Enlarges an image to a larger size by repeating its pixels (nearest
// neighbour): a preview rendered with fewer pixels fills the host's full
// buffers with whole pixels of its own, never blends of them, so depth and
// ids stay values some fragment really had.

#include <cstdint>
#include <vector>

#include "hdHair/image/Image.h"

namespace hdhair {

// Pixel (x, y) of the result is pixel (x * image.width / width, y *
// image.height / height) of `image`, rows from the top down. Throws
// std::invalid_argument for an image without pixels.
Image upscaleNearest(const Image& image, int width, int height);

// The same for one int per pixel (id images); throws std::invalid_argument
// when `values` is not fromWidth x fromHeight.
std::vector<int32_t> upscaleNearest(const std::vector<int32_t>& values, int fromWidth, int fromHeight, int width,
                                    int height);

}  // namespace hdhair
