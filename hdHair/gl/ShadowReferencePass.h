#pragma once
// shadowMode=reference: every fragment each light view sees, kept in
// per-texel linked lists (shadowFragmentList.frag), so that a lookup sums
// the exact opacity in front of any depth with no layers at all
// (shaders/include/shadows.glsl referenceOpacityAt). Slow on purpose: the
// yardstick deep opacity maps are measured against.
//
// All lights share one pool of nodes; each light's lists start in its slot's
// layer of the heads image. A light first counts its fragments (a draw that
// writes nothing), the pool grows to hold them (copied on the GPU), then
// the light draws again and appends. The pool is emptied by reset(), before
// the first light of a frame that rebuilds them (ShadowMapCache rebuilds
// them all together).

#include <cstdint>
#include <vector>

#include "hdHair/gl/GlObjects.h"
#include "hdHair/gl/LightViewDraw.h"
#include "hdHair/gl/SegmentRange.h"
#include "hdHair/gl/StrandGeometry.h"
#include "hdHair/gl/UniformBlocks.h"

namespace hdhair::gl {

constexpr size_t kShadowNodeBytes = 16;  // ShadowNode in shaders/include/shadowFragmentLists.glsl

class ShadowReferencePass {
public:
    ShadowReferencePass();  // a 1x1 heads image and a one-node pool, so the lookup always has them

    // Heads for `slots` lights of resolution^2 texels (contents lost when they change).
    void ensure(int resolution, int slots);
    // Empties the pool.
    void reset();
    // Draws the lists of the light that `light` names as entry 0 into its
    // slot. Returns the nodes it needed; when the pool would outgrow what one
    // shader storage block may address (GL_MAX_SHADER_STORAGE_BLOCK_SIZE) it
    // writes nothing, leaves the slot's lists empty and returns 0 through
    // `written` (the caller warns: that light goes unshadowed).
    uint64_t render(const StrandGeometry& geometry, const std::vector<SegmentRange>& ranges,
                    const FrameUniforms& lightView, const ShadowUniforms& light, bool* written);
    // The heads at image unit 1 and the nodes at storage binding 10
    // (shadowFragmentLists.glsl).
    void bindForLookup() const;

private:
    void drawLists(const StrandGeometry& geometry, const std::vector<SegmentRange>& ranges,
                   const FrameUniforms& lightView, const ShadowUniforms& light, uint32_t first, uint32_t capacity);

    Program program_;
    LightViewDraw draw_;
    Texture heads_;
    Framebuffer framebuffer_;  // no attachments: rasterises resolution^2 without drawing anything
    Buffer nodes_, counter_;
    int resolution_ = 0, slots_ = 0;
    size_t capacity_ = 0, used_ = 0;  // in nodes
    size_t maxNodes_ = 0;
};

}  // namespace hdhair::gl
