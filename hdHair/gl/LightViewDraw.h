#pragma once
// Draws the frame's strands through a light's view, for the passes that
// build shadows (ShadowMapPass, ShadowReferencePass): the strand stages
// (strand.vert/.tesc/.tese) with the light view's frame uniforms (ribbons
// facing the light, or one-texel lines when the program has strand lines,
// tessellated and covered by the rules in the light's pixels; lines of
// straight spans may skip the tessellator, LightViewSpans.h) and the
// shadow uniforms naming the light (entry 0), under whatever program and GL
// state the caller set up.

#include <vector>

#include "hdHair/gl/GlObjects.h"
#include "hdHair/gl/LightViewSpans.h"
#include "hdHair/gl/SegmentRange.h"
#include "hdHair/gl/StrandGeometry.h"
#include "hdHair/gl/UniformBlocks.h"

namespace hdhair::gl {

class LightViewDraw {
public:
    LightViewDraw();

    // Binds the blocks (frame at 0, shadows at 2).
    void bindBlocks(const FrameUniforms& lightView, const ShadowUniforms& light);
    // Binds the blocks, the geometry and `program`, and draws `ranges`
    // unordered.
    void draw(const Program& program, const StrandGeometry& geometry, const std::vector<SegmentRange>& ranges,
              const FrameUniforms& lightView, const ShadowUniforms& light);
    // Strand lines from `spans`' list: its one-segment spans as plain lines
    // with `straightProgram` (strandChord.vert), the rest through the
    // tessellator with `program`.
    void draw(const Program& straightProgram, const Program& program, const StrandGeometry& geometry,
              const LightViewSpans& spans, const FrameUniforms& lightView, const ShadowUniforms& light);

private:
    VertexArray emptyVertexArray_;
    Buffer frameBlock_, shadowBlock_, order_;
};

}  // namespace hdhair::gl
