#pragma once
// The framebuffer a frame is rendered into: linear float colour (RGBA32F, so
// blending and sums of passes keep their precision) and a float depth buffer.

#include <vector>

#include <glm/vec4.hpp>

#include "hdHair/gl/GlObjects.h"

namespace hdhair::gl {

class RenderTarget {
public:
    // Throws std::runtime_error if the driver cannot make the framebuffer.
    RenderTarget(int width, int height);

    int width() const { return width_; }
    int height() const { return height_; }
    // Binds for drawing, sets the viewport and clears colour and depth.
    void bindAndClear(const glm::vec4& clearColor);
    // RGBA floats, rows from the top of the image down.
    std::vector<float> readColor() const;
    // Window-space depth in [0, 1], rows from the top down.
    std::vector<float> readDepth() const;

private:
    int width_, height_;
    Texture color_, depth_;
    Framebuffer framebuffer_;
};

}  // namespace hdhair::gl
