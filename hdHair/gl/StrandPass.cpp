#include "hdHair/gl/StrandPass.h"

#include <algorithm>

#include "hdHair/gl/RenderTarget.h"

namespace hdhair::gl {

StrandPass::StrandPass()
    : program_(createProgram({"strand.vert", "strand.tesc", "strand.tese", "strand.frag"})),
      emptyVertexArray_(createVertexArray()),
      frameBlock_(createBuffer(nullptr, sizeof(FrameUniforms), GL_DYNAMIC_STORAGE_BIT)),
      lightBlock_(createBuffer(nullptr, sizeof(LightUniforms), GL_DYNAMIC_STORAGE_BIT)),
      shadowBlock_(createBuffer(nullptr, sizeof(ShadowUniforms), GL_DYNAMIC_STORAGE_BIT)) {
    checkGlError("setting up the strand pass");
}

void StrandPass::setUniforms(const FrameUniforms& frame, const LightUniforms& lights, const ShadowUniforms& shadows) {
    glNamedBufferSubData(frameBlock_.get(), 0, sizeof(frame), &frame);
    glNamedBufferSubData(lightBlock_.get(), 0, sizeof(lights), &lights);
    glNamedBufferSubData(shadowBlock_.get(), 0, sizeof(shadows), &shadows);
    glBindBufferBase(GL_UNIFORM_BUFFER, 0, frameBlock_.get());
    glBindBufferBase(GL_UNIFORM_BUFFER, 1, lightBlock_.get());
    glBindBufferBase(GL_UNIFORM_BUFFER, 2, shadowBlock_.get());
    maxSegmentsPerSpan_ = frame.maxSegmentsPerSpan;
    orderedDraw_ = frame.orderedDraw != 0;
}

void StrandPass::setDrawOrder(const std::vector<uint32_t>& order) {
    if (order.size() > orderCapacity_ || !orderBuffer_) {
        orderCapacity_ = std::max<size_t>(order.size(), 1);
        orderBuffer_ = createBuffer(nullptr, orderCapacity_ * sizeof(uint32_t), GL_DYNAMIC_STORAGE_BIT);
    }
    if (!order.empty())
        glNamedBufferSubData(orderBuffer_.get(), 0, GLsizeiptr(order.size() * sizeof(uint32_t)), order.data());
    orderedSegments_ = order.size();
}

void StrandPass::drawPatches(const std::vector<SegmentRange>& ranges, float maxSegmentsPerSpan) {
    // Mesa 22.3's llvmpipe draws triangles between unrelated vertices (long
    // spikes across the image, and 50x slower frames) once one draw's
    // tessellator emits too many vertices: examples/dense_clump.usda broke at
    // 22+ segments per span in single draws of 27,900 patches. Draws of at
    // most 2,048 emitted vertices (2 * (level + 1) per patch) render correctly
    // at every level with no measurable cost from the extra draw calls.
    // testRenderBaselines' DenseStrandsAtHighTessellationStayIntact guards it.
    const GLsizei verticesPerPatch = 2 * (GLsizei(maxSegmentsPerSpan) + 1);
    const GLsizei patchesPerDraw = std::max<GLsizei>(1, 2048 / verticesPerPatch);
    glPatchParameteri(GL_PATCH_VERTICES, 4);
    // strand.vert pulls control points by gl_VertexID, which counts from
    // `first`: batches need no offsets of their own.
    for (const SegmentRange& range : ranges) {
        const GLsizei first = GLsizei(range.first), end = GLsizei(range.first + range.count);
        for (GLsizei patch = first; patch < end; patch += patchesPerDraw)
            glDrawArrays(GL_PATCHES, patch * 4, std::min(patchesPerDraw, end - patch) * 4);
    }
}

void StrandPass::draw(const StrandGeometry& geometry, const std::vector<SegmentRange>& ranges,
                      StrandBlending blending) {
    geometry.bind();
    // The shaders declare the order buffer even when they do not read it.
    if (!orderBuffer_) setDrawOrder({});
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, orderBuffer_.get());
    // Ordered: patch p is segment drawOrder[p], so the patches run from 0.
    const std::vector<SegmentRange> ordered{SegmentRange{0, orderedSegments_}};
    const std::vector<SegmentRange>& patches = orderedDraw_ ? ordered : ranges;

    glUseProgram(program_.get());
    glBindVertexArray(emptyVertexArray_.get());
    glEnable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);  // ribbons are seen from both sides
    switch (blending) {
    case StrandBlending::Opaque:
    case StrandBlending::IdsOnly:
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        glDisable(GL_BLEND);
        break;
    case StrandBlending::PremultipliedOver:
        // Sorted far to near, so depth writes would only reject strands that
        // the bins ordered wrongly (Svoboda 2012, section 1.3.3): test only.
        glDepthFunc(GL_LEQUAL);
        glDepthMask(GL_FALSE);
        glEnable(GL_BLEND);
        glBlendEquation(GL_FUNC_ADD);
        glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
        // The nearest depth keeps the least depth written, in any drawing
        // order (MIN ignores the blend factors).
        glBlendEquationi(kNearestDepthOutput, GL_MIN);
        // Integer id images cannot blend: unmasked, they would keep the
        // last fragment drawn, faint or not. The ids pass writes them.
        for (int i = 0; i < 3; ++i)
            glColorMaski(GLuint(kFirstIdOutput + i), GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        break;
    }
    if (blending == StrandBlending::IdsOnly) {
        // Colour was composited already, and the nearest depth must stay
        // the min-blended one (unblended writes would keep the last fragment).
        glColorMaski(kColorOutput, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glColorMaski(kNearestDepthOutput, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    }
    drawPatches(patches, maxSegmentsPerSpan_);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glBlendEquation(GL_FUNC_ADD);
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    glBindVertexArray(0);
    glUseProgram(0);
    checkGlError("drawing strands");
}

}  // namespace hdhair::gl
