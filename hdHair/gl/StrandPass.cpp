#include "hdHair/gl/StrandPass.h"

#include <algorithm>
#include <stdexcept>

#include "hdHair/gl/RenderTarget.h"

namespace hdhair::gl {

StrandPass::StrandPass()
    : programs_({"strand.vert", "strand.tesc", "strand.tese", "strand.geom", "strand.frag"}),
      emptyVertexArray_(createVertexArray()),
      frameBlock_(createBuffer(nullptr, sizeof(FrameUniforms), GL_DYNAMIC_STORAGE_BIT)),
      lightBlock_(createBuffer(nullptr, sizeof(LightUniforms), GL_DYNAMIC_STORAGE_BIT)),
      shadowBlock_(createBuffer(nullptr, sizeof(ShadowUniforms), GL_DYNAMIC_STORAGE_BIT)) {
    checkGlError("setting up the strand pass");
}

void StrandPass::setUniforms(const FrameUniforms& frame, const LightUniforms& lights, const ShadowUniforms& shadows,
                             ShadingFeatures features) {
    program_ = &programs_.get(features);
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

uint64_t StrandPass::takeTriangles() {
    uint64_t total = 0;
    for (size_t i = 0; i < triangleQueriesUsed_; ++i) {
        GLuint64 triangles = 0;
        glGetQueryObjectui64v(triangleQueries_[i].get(), GL_QUERY_RESULT, &triangles);
        total += triangles;
    }
    triangleQueriesUsed_ = 0;
    return total;
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

    if (!program_) throw std::logic_error("StrandPass::draw before setUniforms");
    glUseProgram(program_->get());
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
    // Colour passes are counted; the ids pass draws the same triangles again.
    const bool counted = blending != StrandBlending::IdsOnly;
    if (counted) {
        if (triangleQueriesUsed_ == triangleQueries_.size()) {
            GLuint query = 0;
            glCreateQueries(GL_PRIMITIVES_GENERATED, 1, &query);
            triangleQueries_.emplace_back(query);
        }
        glBeginQuery(GL_PRIMITIVES_GENERATED, triangleQueries_[triangleQueriesUsed_++].get());
    }
    geometry.drawPatches(patches, maxSegmentsPerSpan_);
    if (counted) glEndQuery(GL_PRIMITIVES_GENERATED);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glBlendEquation(GL_FUNC_ADD);
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    glBindVertexArray(0);
    glUseProgram(0);
    checkGlError("drawing strands");
}

}  // namespace hdhair::gl
