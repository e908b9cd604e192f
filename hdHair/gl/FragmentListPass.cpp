#include "hdHair/gl/FragmentListPass.h"

#include "hdHair/gl/GpuMemory.h"
#include "hdHair/gl/RenderTarget.h"
#include "hdHair/gl/StrandPass.h"

namespace hdhair::gl {

namespace {

constexpr GLint kResolveIds = 0;  // uniform location in shaders/fragmentListResolve.frag

}  // namespace

FragmentListPass::FragmentListPass()
    : listPrograms_({"strand.vert", "strand.tesc", "strand.tese", "strand.geom", "strandFragmentList.frag"}),
      resolveProgram_(createProgram({"fullscreen.vert", "fragmentListResolve.frag"})),
      emptyVertexArray_(createVertexArray()),
      counter_(createBuffer(nullptr, 2 * sizeof(uint32_t), GL_DYNAMIC_STORAGE_BIT | GL_MAP_READ_BIT, "fragmentLists")),
      order_(createBuffer(nullptr, sizeof(uint32_t), 0, "fragmentLists")) {
    checkGlError("setting up exact transparency");
}

uint64_t FragmentListPass::render(const StrandGeometry& geometry, const std::vector<SegmentRange>& ranges, int width,
                                  int height, size_t capacity, float maxSegmentsPerSpan, bool writeIds,
                                  ShadingFeatures features) {
    const Program& listProgram = listPrograms_.get(features);
    if (width != headsWidth_ || height != headsHeight_) {
        GLuint name = 0;
        glCreateTextures(GL_TEXTURE_2D, 1, &name);
        heads_ = Texture(name);
        glTextureStorage2D(heads_.get(), 1, GL_R32UI, width, height);
        recordTextureStorage(heads_.get(), GL_R32UI, width, height, 1, 0, "fragmentLists");
        headsWidth_ = width;
        headsHeight_ = height;
    }
    if (capacity != nodeCapacity_) {
        nodes_ = createBuffer(nullptr, std::max<size_t>(capacity, 1) * kFragmentNodeBytes, 0, "fragmentLists");
        nodeCapacity_ = capacity;
    }
    const GLuint listEnd = 0xffffffffu;
    glClearTexImage(heads_.get(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &listEnd);
    const uint32_t counter[2] = {0, uint32_t(std::min<size_t>(capacity, 0xffffffffu))};
    glNamedBufferSubData(counter_.get(), 0, sizeof counter, counter);

    geometry.bind();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, order_.get());  // declared, unread (no ordering needed)
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, nodes_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, counter_.get());
    glBindImageTexture(0, heads_.get(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    glBindVertexArray(emptyVertexArray_.get());

    // Pass 1: lists. Opaque geometry's depth rejects hidden fragments; the
    // strands themselves write nothing to the framebuffer.
    glUseProgram(listProgram.get());
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    // Every draw buffer: the list shader has no outputs, so whatever reached
    // an unmasked attachment would be undefined.
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    geometry.drawPatches(ranges, maxSegmentsPerSpan);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);

    // Pass 2: resolve every pixel over what the frame holds (opaque meshes,
    // or nothing): colour composited (ONE, ONE_MINUS_SRC_ALPHA) and the
    // nearest depth min-blended, then the ids where a listed fragment
    // defines them (integer images cannot blend, so they take a draw of
    // their own that discards elsewhere).
    glUseProgram(resolveProgram_.get());
    glDisable(GL_DEPTH_TEST);
    glProgramUniform1i(resolveProgram_.get(), kResolveIds, 0);
    for (int id = 0; id < 3; ++id) glColorMaski(GLuint(kFirstIdOutput + id), GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glEnablei(GL_BLEND, kColorOutput);
    glBlendEquationi(kColorOutput, GL_FUNC_ADD);
    glBlendFunci(kColorOutput, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glEnablei(GL_BLEND, kNearestDepthOutput);
    glBlendEquationi(kNearestDepthOutput, GL_MIN);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    if (writeIds) {
        glProgramUniform1i(resolveProgram_.get(), kResolveIds, 1);
        glColorMaski(kColorOutput, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glColorMaski(kNearestDepthOutput, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    }
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);

    uint32_t offered = 0;
    glGetNamedBufferSubData(counter_.get(), 0, sizeof offered, &offered);
    glBindVertexArray(0);
    glUseProgram(0);
    checkGlError("rendering exact transparency");
    return offered;
}

}  // namespace hdhair::gl
