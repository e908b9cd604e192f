#pragma once
// The framebuffer a frame is rendered into: linear float colour (RGBA32F, so
// blending and sums of passes keep their precision), a float depth buffer,
// and, only when asked for, three 32-bit integer id images (prim, instance,
// element) for picking and selection in Hydra hosts.

#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

#include "hdHair/gl/GlObjects.h"

namespace hdhair::gl {

class RenderTarget {
public:
    // Throws std::runtime_error if the driver cannot make the framebuffer.
    RenderTarget(int width, int height, bool withIds);

    int width() const { return width_; }
    int height() const { return height_; }
    bool hasIds() const { return withIds_; }
    // Binds for drawing, sets the viewport and clears colour and depth (and
    // the ids to -1, Hydra's "nothing here").
    void bindAndClear(const glm::vec4& clearColor);
    // RGBA floats, rows from the top of the image down.
    std::vector<float> readColor() const;
    // Window-space depth in [0, 1], rows from the top down.
    std::vector<float> readDepth() const;
    // Id image `index` (0 prim, 1 instance, 2 element), rows from the top down.
    std::vector<int32_t> readIds(int index) const;

private:
    int width_, height_;
    bool withIds_;
    Texture color_, depth_;
    Texture ids_[3];
    Framebuffer framebuffer_;
};

}  // namespace hdhair::gl
