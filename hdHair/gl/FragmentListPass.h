#pragma once
// Exact transparency: every strand fragment goes into a per-pixel linked list
// in a storage buffer (pass 1), then each pixel sorts its list by depth and
// composites it exactly (pass 2). Slow on purpose: it is the ground truth
// that bin sorting is measured against. The lists' memory is bounded; a frame
// that needs more reports how much, and the renderer falls back.

#include <cstdint>
#include <vector>

#include "hdHair/gl/GlObjects.h"
#include "hdHair/gl/SegmentRange.h"
#include "hdHair/gl/ShadingPrograms.h"
#include "hdHair/gl/StrandGeometry.h"

namespace hdhair::gl {

constexpr size_t kFragmentNodeBytes = 32;  // FragmentNode in shaders/include/fragmentLists.glsl

class FragmentListPass {
public:
    FragmentListPass();  // compiles the resolve program; list programs as render() asks for them

    // Renders into the currently bound framebuffer, over what it holds: the
    // strands' colour is composited over it, their nearest depth min-blended
    // with it, and their ids (with `writeIds`, when the target has ids)
    // written where a strand fragment defines them; the depth buffer is
    // tested, not written, so opaque geometry drawn before hides what is
    // behind it. The frame and light uniform blocks must be bound
    // (StrandPass::setUniforms). Depth and ids follow
    // hdHair/render/NearestStrandRule.h.
    // Returns how many fragments the strands produced; more than
    // `capacity` means the image is incomplete and must not be used.
    // `ranges`: the drawn prims' segments. `features`: the shading the list
    // program compiles, as for StrandPass::setUniforms.
    uint64_t render(const StrandGeometry& geometry, const std::vector<SegmentRange>& ranges, int width, int height,
                    size_t capacity, float maxSegmentsPerSpan, bool writeIds, ShadingFeatures features);

private:
    ShadingPrograms listPrograms_;
    Program resolveProgram_;
    VertexArray emptyVertexArray_;
    Texture heads_;
    int headsWidth_ = 0, headsHeight_ = 0;
    Buffer nodes_, counter_, order_;
    size_t nodeCapacity_ = 0;
};

}  // namespace hdhair::gl
