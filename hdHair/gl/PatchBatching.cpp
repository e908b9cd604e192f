#include "hdHair/gl/PatchBatching.h"

#include <algorithm>

#include <glad/gl.h>

namespace hdhair::gl {

namespace {
constexpr int kLlvmpipeEmittedVertices = 2048;
}

PatchBatching PatchBatching::forced(bool batched) {
    return batched ? PatchBatching{kLlvmpipeEmittedVertices, "drawBatching=on"} : PatchBatching{0, "drawBatching=off"};
}

PatchBatching PatchBatching::forDriver(const std::string& glRenderer) {
    if (glRenderer.find("llvmpipe") != std::string::npos)
        return {kLlvmpipeEmittedVertices, "llvmpipe joins unrelated vertices in larger tessellated draws"};
    return {0, "the driver draws whole ranges"};
}

std::string PatchBatching::describe() const {
    if (maxEmittedVertices == 0) return "one draw a prim range (" + reason + ")";
    return "draws of at most " + std::to_string(maxEmittedVertices) + " emitted vertices (" + reason + ")";
}

void PatchBatching::draw(const std::vector<SegmentRange>& ranges, float maxSegmentsPerSpan) const {
    const GLsizei verticesPerPatch = 2 * (GLsizei(maxSegmentsPerSpan) + 1);
    glPatchParameteri(GL_PATCH_VERTICES, 4);
    // strand.vert pulls control points by gl_VertexID, which counts from
    // `first`: batches need no offsets of their own.
    GLsync previous = nullptr;
    int draws = 0;
    for (const SegmentRange& range : ranges) {
        const GLsizei first = GLsizei(range.first), end = GLsizei(range.first + range.count);
        const GLsizei patchesPerDraw =
            maxEmittedVertices > 0 ? std::max<GLsizei>(1, maxEmittedVertices / verticesPerPatch) : end - first;
        for (GLsizei patch = first; patch < end; patch += patchesPerDraw) {
            glDrawArrays(GL_PATCHES, patch * 4, std::min(patchesPerDraw, end - patch) * 4);
            if (maxEmittedVertices == 0 || ++draws % kDrawsBetweenFences != 0) continue;
            // Bound the driver's queue: wait for the draws before the last
            // fence while the ones since keep it busy.
            GLsync fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
            if (previous) {
                glClientWaitSync(previous, GL_SYNC_FLUSH_COMMANDS_BIT, GLuint64(600) * 1000000000u);
                glDeleteSync(previous);
            }
            previous = fence;
        }
    }
    if (previous) glDeleteSync(previous);
}

}  // namespace hdhair::gl
