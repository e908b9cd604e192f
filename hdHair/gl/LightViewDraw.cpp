#include "hdHair/gl/LightViewDraw.h"

#include "hdHair/gl/StrandPass.h"

namespace hdhair::gl {

LightViewDraw::LightViewDraw()
    : emptyVertexArray_(createVertexArray()),
      frameBlock_(createBuffer(nullptr, sizeof(FrameUniforms), GL_DYNAMIC_STORAGE_BIT)),
      shadowBlock_(createBuffer(nullptr, sizeof(ShadowUniforms), GL_DYNAMIC_STORAGE_BIT)),
      order_(createBuffer(nullptr, sizeof(uint32_t))) {}

void LightViewDraw::bindBlocks(const FrameUniforms& lightView, const ShadowUniforms& light) {
    glNamedBufferSubData(frameBlock_.get(), 0, sizeof(lightView), &lightView);
    glNamedBufferSubData(shadowBlock_.get(), 0, sizeof(light), &light);
    glBindBufferBase(GL_UNIFORM_BUFFER, 0, frameBlock_.get());
    glBindBufferBase(GL_UNIFORM_BUFFER, 2, shadowBlock_.get());
}

namespace {
// The state every light-view draw runs under, set while alive.
class LightViewState {
public:
    explicit LightViewState(const VertexArray& emptyVertexArray) {
        glBindVertexArray(emptyVertexArray.get());
        glDisable(GL_DEPTH_TEST);
        glDepthMask(GL_FALSE);
        glDisable(GL_CULL_FACE);  // ribbons are seen from both sides
    }
    ~LightViewState() {
        glDepthMask(GL_TRUE);
        glBindVertexArray(0);
        glUseProgram(0);
    }
    LightViewState(const LightViewState&) = delete;
    LightViewState& operator=(const LightViewState&) = delete;
};
}  // namespace

void LightViewDraw::draw(const Program& program, const StrandGeometry& geometry,
                         const std::vector<SegmentRange>& ranges, const FrameUniforms& lightView,
                         const ShadowUniforms& light) {
    bindBlocks(lightView, light);
    geometry.bind();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, order_.get());  // declared, unread (orderedDraw is 0)
    LightViewState state(emptyVertexArray_);
    glUseProgram(program.get());
    geometry.drawPatches(ranges, lightView.maxSegmentsPerSpan);
}

void LightViewDraw::draw(const Program& straightProgram, const Program& program, const StrandGeometry& geometry,
                         const LightViewSpans& spans, const FrameUniforms& lightView, const ShadowUniforms& light) {
    // The tessellated spans come through the list too, after the straight.
    FrameUniforms listed = lightView;
    listed.orderedDraw = 1;
    bindBlocks(listed, light);
    geometry.bind();
    spans.bindList();
    LightViewState state(emptyVertexArray_);
    if (spans.straight() > 0) {
        glUseProgram(straightProgram.get());
        glDrawArrays(GL_LINES, 0, GLsizei(2 * spans.straight()));
    }
    if (spans.tessellated() > 0) {
        glUseProgram(program.get());
        geometry.drawPatches({SegmentRange{spans.straight(), spans.tessellated()}}, lightView.maxSegmentsPerSpan);
    }
}

}  // namespace hdhair::gl
