#include "hdHair/gl/LightBatchAccumulation.h"

#include "hdHair/gl/RenderTarget.h"

namespace hdhair::gl {

LightBatchAccumulation::LightBatchAccumulation()
    : program_(createProgram({"fullscreen.vert", "accumulateLightBatch.frag"})),
      emptyVertexArray_(createVertexArray()) {}

void LightBatchAccumulation::add(RenderTarget& frame, const RenderTarget& batch) {
    frame.bindResolvedColorForDrawing();
    glUseProgram(program_.get());
    glBindVertexArray(emptyVertexArray_.get());
    glBindTextureUnit(0, batch.resolvedColorTexture());
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFuncSeparate(GL_ONE, GL_ONE, GL_ZERO, GL_ONE);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_BLEND);
    glEnable(GL_DEPTH_TEST);
    glBindTextureUnit(0, 0);
    glBindVertexArray(0);
    glUseProgram(0);
    checkGlError("adding a light batch");
}

}  // namespace hdhair::gl
