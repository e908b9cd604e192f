#pragma once
// The framebuffer a frame is rendered into: linear float colour (RGBA32F, so
// blending keeps its precision), a float depth buffer, and, only when asked
// for, three 32-bit integer id images (prim, instance, element) for picking
// and selection in Hydra hosts. With samples > 0 the frame is drawn
// multisampled and resolved (colour averaged; depth and ids take one sample,
// as GL's blit does for them) before it is read back.

#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

#include "hdHair/gl/GlObjects.h"

namespace hdhair::gl {

class RenderTarget {
public:
    // Throws std::runtime_error if the driver cannot make the framebuffer.
    RenderTarget(int width, int height, bool withIds, int samples = 0);

    int width() const { return width_; }
    int height() const { return height_; }
    bool hasIds() const { return withIds_; }
    int samples() const { return samples_; }
    // Binds for drawing, sets the viewport and clears colour and depth (and
    // the ids to -1, Hydra's "nothing here").
    void bindAndClear(const glm::vec4& clearColor);
    // After drawing: resolves multisampled images (nothing to do otherwise).
    void resolve();
    // The single-sampled colour (resolved when multisampled), and a binding
    // of it for drawing only colour onto it (light batches add up there).
    GLuint resolvedColorTexture() const;
    void bindResolvedColorForDrawing();
    // RGBA floats, rows from the top of the image down.
    std::vector<float> readColor() const;
    // Window-space depth in [0, 1], rows from the top down.
    std::vector<float> readDepth() const;
    // Id image `index` (0 prim, 1 instance, 2 element), rows from the top down.
    std::vector<int32_t> readIds(int index) const;

private:
    struct Attachments {
        Texture color, depth, ids[3];
        Framebuffer framebuffer;
    };
    void create(Attachments& attachments, int samples);

    int width_, height_;
    bool withIds_;
    int samples_;
    Attachments draw_;      // what passes render into (multisampled when samples_ > 0)
    Attachments resolved_;  // single-sampled copy, only with samples_ > 0
};

}  // namespace hdhair::gl
