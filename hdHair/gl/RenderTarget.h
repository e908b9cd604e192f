#pragma once
// The framebuffer a frame is rendered into: linear float colour (RGBA32F, so
// blending keeps its precision), a float depth buffer, and, only when asked
// for, three 32-bit integer id images (prim, instance, element) for picking
// and selection in Hydra hosts, and a nearest-depth image for blended frames.
// With samples > 0 the frame is drawn multisampled and resolved (colour
// averaged; depth and ids take one sample, as GL's blit does for them) before
// it is read back.
//
// Blended strands do not write the depth buffer (they are drawn far to near,
// or in no order at all), so blended frames take their depth from the
// nearest-depth image instead: R32F, cleared to 1 and min-blended, written by
// the strand shaders at output kNearestDepthOutput with the window depth of
// each fragment that may define it, and by the meshes, drawn before them
// (hdHair/plan/NearestStrandRule.h).

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

#include "hdHair/gl/GlObjects.h"

namespace hdhair::gl {

// Fragment shader outputs (layout locations) and the attachments they draw to.
constexpr int kColorOutput = 0;
constexpr int kFirstIdOutput = 1;          // prim, instance, element: 1, 2, 3
constexpr int kNearestDepthOutput = 4;     // strand.frag, mesh.frag and fragmentListResolve.frag
constexpr int kOutputCount = 5;

// Which images a render target has besides colour and depth.
struct RenderTargetImages {
    bool ids = false;           // primId, instanceId, elementId
    bool nearestDepth = false;  // blended frames' depth (see above)
    int samples = 0;            // multisampling; 0 for none
    bool operator==(const RenderTargetImages& other) const {
        return ids == other.ids && nearestDepth == other.nearestDepth && samples == other.samples;
    }
    bool operator!=(const RenderTargetImages& other) const { return !(*this == other); }
};

class RenderTarget {
public:
    // Throws std::runtime_error if the driver cannot make the framebuffer.
    RenderTarget(int width, int height, const RenderTargetImages& images);

    int width() const { return width_; }
    int height() const { return height_; }
    const RenderTargetImages& images() const { return images_; }
    // Binds for drawing into every image it has, and sets the viewport.
    void bind();
    // bind(), then clears colour, depth and the nearest depth to 1, and the
    // ids to -1 (Hydra's "nothing here").
    void bindAndClear(const glm::vec4& clearColor);
    // After drawing: resolves multisampled images (nothing to do otherwise).
    void resolve();
    // The single-sampled colour (resolved when multisampled), and a binding
    // of it for drawing only colour onto it (light batches add up there).
    GLuint resolvedColorTexture() const;
    // The depth buffer passes draw against (multisampled when samples > 0):
    // what the compute rasteriser tests its fragments against.
    GLuint depthTexture() const { return draw_.depth.get(); }
    void bindResolvedColorForDrawing();
    // RGBA floats, rows from the top of the image down.
    std::vector<float> readColor() const;
    // The frame's window-space depth in [0, 1], rows from the top down: the
    // nearest-depth image when the target has one, else the depth buffer.
    std::vector<float> readDepth() const;
    // Id image `index` (0 prim, 1 instance, 2 element), rows from the top down.
    std::vector<int32_t> readIds(int index) const;

private:
    struct Attachments {
        Texture color, depth, ids[3], nearestDepth;
        Framebuffer framebuffer;
    };
    void create(Attachments& attachments, int samples);
    // Every output this target has an image for, in output order; NONE for the others.
    std::array<GLenum, kOutputCount> drawBuffers() const;
    GLuint readFramebuffer() const;

    int width_, height_;
    RenderTargetImages images_;
    Attachments draw_;      // what passes render into (multisampled when samples > 0)
    Attachments resolved_;  // single-sampled copy, only with samples > 0
};

}  // namespace hdhair::gl
