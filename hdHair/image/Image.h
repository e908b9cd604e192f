#pragma once
// A float image in memory: rows from the top down, channels interleaved.
// Colour images are scene-linear RGBA with pre-multiplied alpha.

#include <cstddef>
#include <vector>

namespace hdhair {

struct Image {
    int width = 0;
    int height = 0;
    int channels = 0;
    std::vector<float> pixels;  // width * height * channels

    Image() = default;
    Image(int w, int h, int c, float fill = 0.0f)
        : width(w), height(h), channels(c), pixels(size_t(w) * size_t(h) * size_t(c), fill) {}

    float& at(int x, int y, int c) { return pixels[(size_t(y) * size_t(width) + size_t(x)) * size_t(channels) + size_t(c)]; }
    float at(int x, int y, int c) const { return pixels[(size_t(y) * size_t(width) + size_t(x)) * size_t(channels) + size_t(c)]; }
};

}  // namespace hdhair
