#pragma once
// Which spans of a light view go to the rasteriser as they are and which go
// through the tessellator, when the view draws strand lines
// (shadowStrandLines=auto). On llvmpipe a patch costs its vertex, control
// and evaluation stages on the one thread that draws, even when it emits a
// single segment, and at the light views' tolerance (half a texel) most
// spans are straight, and drawing them as plain lines (strandChord.vert)
// saves that work (docs/how-it-works.md, "Straight spans skip the
// tessellator", has the measurement).
//
// lightViewLevels.comp asks strandTessellationLevel.glsl, the very rule
// strand.tesc applies, for every span of the drawn ranges in the light's
// view; the levels come back to the CPU, which lists the one-segment spans
// first and the others after them (each group in drawing order; culled spans,
// level 0, in neither) into a buffer the draws read as their draw order
// (binding 4). Made by the depth pass and kept for the opacity pass of the
// same view, which needs the same list.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "hdHair/gl/GlObjects.h"
#include "hdHair/gl/SegmentRange.h"
#include "hdHair/gl/StrandGeometry.h"
#include "hdHair/gl/UniformBlocks.h"

namespace hdhair::gl {

class LightViewSpans {
public:
    // Lists the spans of `ranges` in the view of `lightView`, whose frame
    // uniforms must be bound at 0 (LightViewDraw::bindBlocks). Compiles
    // lightViewLevels.comp the first time; throws on driver errors.
    void build(const StrandGeometry& geometry, const std::vector<SegmentRange>& ranges,
               const FrameUniforms& lightView);
    // Whether the list is the one `build` would make for these: the same
    // ranges and view uniforms, with the geometry unchanged since, which
    // the caller knows (a light's opacity pass follows its depth pass in the
    // same frame).
    bool builtFor(const std::vector<SegmentRange>& ranges, const FrameUniforms& lightView) const;

    size_t straight() const { return straight_; }        // listed first: one segment each
    size_t tessellated() const { return tessellated_; }  // after them
    // Binds the list as the draw order (binding 4).
    void bindList() const;

private:
    Program levelsProgram_;
    Buffer levels_, list_;
    size_t levelCapacity_ = 0, listCapacity_ = 0;
    std::vector<uint32_t> readLevels_, listed_;
    size_t straight_ = 0, tessellated_ = 0;
    std::vector<SegmentRange> builtRanges_;
    FrameUniforms builtView_{};
    bool built_ = false;
};

}  // namespace hdhair::gl
