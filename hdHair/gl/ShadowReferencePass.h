#pragma once
// shadowMode=reference: every fragment each light view sees, kept in
// per-texel linked lists (shadowFragmentList.frag), so that a lookup sums
// the exact opacity in front of any depth with no layers at all
// (shaders/include/shadows.glsl referenceOpacityAt). Slow on purpose: the
// yardstick deep opacity maps are measured against.
//
// All lights share the nodes; each light's lists start in its slot's layer
// of the heads image. A light first counts its fragments (a draw that writes
// nothing), the nodes grow to hold them, then the light draws again and
// appends. The nodes are emptied by reset(), before the first light of a
// frame that rebuilds them (ShadowMapCache rebuilds them all together).
// One storage block addresses at most GL_MAX_SHADER_STORAGE_BLOCK_SIZE
// bytes (128 MB on llvmpipe), so the nodes are kept in up to
// kShadowNodePools pools (shaders/include/shadowFragmentLists.glsl): the
// first grows (copied on the GPU) up to that size, the others are added at
// that size.

#include <cstdint>
#include <vector>

#include "hdHair/gl/GlObjects.h"
#include "hdHair/gl/LightViewDraw.h"
#include "hdHair/gl/SegmentRange.h"
#include "hdHair/gl/StrandGeometry.h"
#include "hdHair/gl/UniformBlocks.h"

namespace hdhair::gl {

constexpr size_t kShadowNodeBytes = 12;  // ShadowNode in shaders/include/shadowFragmentLists.glsl
constexpr int kShadowNodePools = 4;      // HDHAIR_SHADOW_NODE_POOLS

class ShadowReferencePass {
public:
    ShadowReferencePass();  // a 1x1 heads image and a one-node pool, so the lookup always has them

    // Heads for `slots` lights of resolution^2 texels (contents lost when they change).
    void ensure(int resolution, int slots);
    // Empties the pool.
    void reset();
    // Draws the lists of the light that `light` names as entry 0 into its
    // slot. Returns the nodes it needed; when the nodes would outgrow the
    // pools (kShadowNodePools blocks of GL_MAX_SHADER_STORAGE_BLOCK_SIZE) it
    // writes nothing, leaves the slot's lists empty and sets `written` false
    // (the caller warns: that light goes unshadowed).
    uint64_t render(const StrandGeometry& geometry, const std::vector<SegmentRange>& ranges,
                    const FrameUniforms& lightView, const ShadowUniforms& light, bool* written);
    // The heads at image unit 1 and the node pools at storage bindings 10,
    // 12, 13 and 14 (shadowFragmentLists.glsl).
    void bindForLookup() const;

private:
    void drawLists(const StrandGeometry& geometry, const std::vector<SegmentRange>& ranges,
                   const FrameUniforms& lightView, const ShadowUniforms& light, uint32_t first, uint32_t capacity);
    // Room for `nodes` in all; false when the pools cannot hold them.
    bool reserve(size_t nodes);
    size_t capacity() const { return poolSize_ * pools_.size(); }

    Program program_;
    LightViewDraw draw_;
    Texture heads_;
    Framebuffer framebuffer_;  // no attachments: rasterises resolution^2 without drawing anything
    std::vector<Buffer> pools_;  // the first always; the others only once it is full size
    Buffer unusedPool_, counter_;
    int resolution_ = 0, slots_ = 0;
    size_t poolSize_ = 1, used_ = 0;  // in nodes
    size_t maxNodes_ = 0;             // what one storage block addresses
};

}  // namespace hdhair::gl
