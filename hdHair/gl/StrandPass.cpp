#include "hdHair/gl/StrandPass.h"

#include <algorithm>

#include "hdHair/curves/PreparedCurves.h"

namespace hdhair::gl {

StrandBuffer::StrandBuffer(const PreparedCurves& curves)
    : buffer_(createBuffer(curves.controlPoints.data(),
                           curves.controlPoints.size() * sizeof(StrandControlPoint))),
      segmentCurves_(createBuffer(curves.segmentCurve.data(), curves.segmentCurve.size() * sizeof(uint32_t))),
      controlPointCount_(static_cast<GLsizei>(curves.controlPoints.size())) {}

StrandPass::StrandPass()
    : program_(createProgram({"strand.vert", "strand.tesc", "strand.tese", "strand.frag"})),
      vertexArray_(createVertexArray()),
      frameBlock_(createBuffer(nullptr, sizeof(FrameUniforms), GL_DYNAMIC_STORAGE_BIT)),
      lightBlock_(createBuffer(nullptr, sizeof(LightUniforms), GL_DYNAMIC_STORAGE_BIT)) {
    // Attribute layout of StrandControlPoint: position, width, color, opacity.
    GLuint vao = vertexArray_.get();
    const GLuint offsets[4] = {offsetof(StrandControlPoint, position), offsetof(StrandControlPoint, width),
                               offsetof(StrandControlPoint, color), offsetof(StrandControlPoint, opacity)};
    const GLint sizes[4] = {3, 1, 3, 1};
    for (GLuint attribute = 0; attribute < 4; ++attribute) {
        glEnableVertexArrayAttrib(vao, attribute);
        glVertexArrayAttribFormat(vao, attribute, sizes[attribute], GL_FLOAT, GL_FALSE, offsets[attribute]);
        glVertexArrayAttribBinding(vao, attribute, 0);
    }
    checkGlError("setting up the strand pass");
}

void StrandPass::draw(const FrameUniforms& frame, const LightUniforms& lights, const std::vector<StrandDraw>& draws) {
    glNamedBufferSubData(frameBlock_.get(), 0, sizeof(frame), &frame);
    glNamedBufferSubData(lightBlock_.get(), 0, sizeof(lights), &lights);
    glBindBufferBase(GL_UNIFORM_BUFFER, 0, frameBlock_.get());
    glBindBufferBase(GL_UNIFORM_BUFFER, 1, lightBlock_.get());

    glUseProgram(program_.get());
    glBindVertexArray(vertexArray_.get());
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);  // ribbons are seen from both sides
    glPatchParameteri(GL_PATCH_VERTICES, 4);
    // Mesa 22.3's llvmpipe draws triangles between unrelated vertices (long
    // spikes across the image, and 50x slower frames) once one draw's
    // tessellator emits too many vertices: examples/dense_clump.usda broke at
    // 22+ segments per span in single draws of 27,900 patches. Draws of at
    // most 2,048 emitted vertices (2 * (level + 1) per patch) render correctly
    // at every level with no measurable cost from the extra draw calls.
    // testRenderBaselines' DenseStrandsAtHighTessellationStayIntact guards it.
    const GLsizei verticesPerPatch = 2 * (GLsizei(frame.maxSegmentsPerSpan) + 1);
    const GLsizei patchesPerDraw = std::max<GLsizei>(1, 2048 / verticesPerPatch);
    for (const StrandDraw& draw : draws) {
        const StrandBuffer* strand = draw.strands;
        if (strand->controlPointCount() == 0) continue;
        glVertexArrayVertexBuffer(vertexArray_.get(), 0, strand->buffer(), 0, sizeof(StrandControlPoint));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, strand->segmentCurves());
        GLsizei patches = strand->controlPointCount() / 4;
        for (GLsizei first = 0; first < patches; first += patchesPerDraw) {
            glUniform2i(0, draw.primId, first);  // drawIds in strand.tese and strand.frag
            glDrawArrays(GL_PATCHES, first * 4, std::min(patchesPerDraw, patches - first) * 4);
        }
    }
    glBindVertexArray(0);
    glUseProgram(0);
    checkGlError("drawing strands");
}

}  // namespace hdhair::gl
