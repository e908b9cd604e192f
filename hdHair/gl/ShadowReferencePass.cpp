#include "hdHair/gl/ShadowReferencePass.h"

#include <algorithm>

namespace hdhair::gl {

namespace {

constexpr GLuint kListEnd = 0xffffffffu;  // HDHAIR_SHADOW_LIST_END

}  // namespace

ShadowReferencePass::ShadowReferencePass()
    : program_(createProgram({"strand.vert", "strand.tesc", "strand.tese", "shadowFragmentList.frag"})),
      nodes_(createBuffer(nullptr, kShadowNodeBytes, GL_DYNAMIC_STORAGE_BIT)),
      counter_(createBuffer(nullptr, 2 * sizeof(uint32_t), GL_DYNAMIC_STORAGE_BIT | GL_MAP_READ_BIT)),
      capacity_(1) {
    GLint64 maxBytes = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBytes);
    maxNodes_ = size_t(maxBytes) / kShadowNodeBytes;
    ensure(1, 1);
    checkGlError("setting up the shadow reference");
}

void ShadowReferencePass::ensure(int resolution, int slots) {
    if (resolution == resolution_ && slots == slots_) return;
    resolution_ = resolution;
    slots_ = slots;
    GLuint name = 0;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &name);
    heads_ = Texture(name);
    glTextureStorage3D(heads_.get(), 1, GL_R32UI, resolution, resolution, slots);
    glClearTexImage(heads_.get(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &kListEnd);
    glCreateFramebuffers(1, &name);
    framebuffer_ = Framebuffer(name);
    glNamedFramebufferParameteri(framebuffer_.get(), GL_FRAMEBUFFER_DEFAULT_WIDTH, resolution);
    glNamedFramebufferParameteri(framebuffer_.get(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, resolution);
    checkGlError("allocating shadow reference lists");
}

void ShadowReferencePass::reset() { used_ = 0; }

void ShadowReferencePass::drawLists(const StrandGeometry& geometry, const std::vector<SegmentRange>& ranges,
                                    const FrameUniforms& lightView, const ShadowUniforms& light, uint32_t first,
                                    uint32_t capacity) {
    const uint32_t counter[2] = {first, capacity};
    glNamedBufferSubData(counter_.get(), 0, sizeof counter, counter);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 10, nodes_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 11, counter_.get());
    glBindImageTexture(1, heads_.get(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32UI);
    // Nothing is drawn to any image: the lists are all the output.
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.get());
    glViewport(0, 0, resolution_, resolution_);
    glDisable(GL_BLEND);
    draw_.draw(program_, geometry, ranges, lightView, light);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

uint64_t ShadowReferencePass::render(const StrandGeometry& geometry, const std::vector<SegmentRange>& ranges,
                                     const FrameUniforms& lightView, const ShadowUniforms& light, bool* written) {
    const int slot = int(light.lightMap[0].x);
    glClearTexSubImage(heads_.get(), 0, 0, 0, slot, resolution_, resolution_, 1, GL_RED_INTEGER, GL_UNSIGNED_INT,
                       &kListEnd);
    // Count: every fragment is offered at or past the capacity, so none is written.
    drawLists(geometry, ranges, lightView, light, 0, 0);
    uint32_t offered = 0;
    glGetNamedBufferSubData(counter_.get(), 0, sizeof offered, &offered);
    const size_t needed = used_ + offered;
    if (needed > maxNodes_) {
        *written = false;
        return offered;
    }
    if (needed > capacity_) {
        const size_t capacity = std::min(maxNodes_, std::max(needed, capacity_ + capacity_ / 2));
        Buffer grown = createBuffer(nullptr, capacity * kShadowNodeBytes, GL_DYNAMIC_STORAGE_BIT);
        if (used_ > 0)
            glCopyNamedBufferSubData(nodes_.get(), grown.get(), 0, 0, GLsizeiptr(used_ * kShadowNodeBytes));
        nodes_ = std::move(grown);
        capacity_ = capacity;
    }
    drawLists(geometry, ranges, lightView, light, uint32_t(used_), uint32_t(capacity_));
    used_ = needed;
    *written = true;
    checkGlError("drawing shadow reference lists");
    return offered;
}

void ShadowReferencePass::bindForLookup() const {
    glBindImageTexture(1, heads_.get(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32UI);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 10, nodes_.get());
}

}  // namespace hdhair::gl
