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

void LightViewDraw::draw(const Program& program, const StrandGeometry& geometry,
                         const std::vector<SegmentRange>& ranges, const FrameUniforms& lightView,
                         const ShadowUniforms& light) {
    bindBlocks(lightView, light);
    geometry.bind();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, order_.get());  // declared, unread (orderedDraw is 0)
    glBindVertexArray(emptyVertexArray_.get());
    glUseProgram(program.get());
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glDisable(GL_CULL_FACE);  // ribbons are seen from both sides
    geometry.drawPatches(ranges, lightView.maxSegmentsPerSpan);
    glDepthMask(GL_TRUE);
    glBindVertexArray(0);
    glUseProgram(0);
}

}  // namespace hdhair::gl
