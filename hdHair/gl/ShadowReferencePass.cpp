#include "hdHair/gl/ShadowReferencePass.h"

#include <algorithm>

#include "hdHair/gl/GpuMemory.h"

namespace hdhair::gl {

namespace {

constexpr GLuint kListEnd = 0xffffffffu;  // HDHAIR_SHADOW_LIST_END

}  // namespace

ShadowReferencePass::ShadowReferencePass()
    : program_(createProgram({"strand.vert", "strand.tesc", "strand.tese", "strand.geom", "shadowFragmentList.frag"})),
      unusedPool_(createBuffer(nullptr, kShadowNodeBytes, GL_DYNAMIC_STORAGE_BIT, "shadowReference")),
      counter_(createBuffer(nullptr, 2 * sizeof(uint32_t), GL_DYNAMIC_STORAGE_BIT | GL_MAP_READ_BIT, "shadowReference")) {
    pools_.push_back(createBuffer(nullptr, kShadowNodeBytes, GL_DYNAMIC_STORAGE_BIT, "shadowReference"));
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
    recordTextureStorage(heads_.get(), GL_R32UI, resolution, resolution, slots, 0, "shadowReference");
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
    bindForLookup();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 11, counter_.get());
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
    if (!reserve(needed)) {
        *written = false;
        return offered;
    }
    drawLists(geometry, ranges, lightView, light, uint32_t(used_), uint32_t(capacity()));
    used_ = needed;
    *written = true;
    checkGlError("drawing shadow reference lists");
    return offered;
}

bool ShadowReferencePass::reserve(size_t nodes) {
    if (nodes <= capacity()) return true;
    if (nodes > maxNodes_ * size_t(kShadowNodePools)) return false;
    // The first pool grows, keeping its nodes, up to what a block addresses.
    if (pools_.size() == 1 && poolSize_ < maxNodes_) {
        const size_t size = std::min(maxNodes_, std::max(nodes, poolSize_ + poolSize_ / 2));
        Buffer grown = createBuffer(nullptr, size * kShadowNodeBytes, GL_DYNAMIC_STORAGE_BIT, "shadowReference");
        if (used_ > 0) glCopyNamedBufferSubData(pools_[0].get(), grown.get(), 0, 0, GLsizeiptr(used_ * kShadowNodeBytes));
        pools_[0] = std::move(grown);
        poolSize_ = size;
    }
    // Then pools of that size are added.
    while (capacity() < nodes)
        pools_.push_back(createBuffer(nullptr, poolSize_ * kShadowNodeBytes, GL_DYNAMIC_STORAGE_BIT, "shadowReference"));
    return true;
}

void ShadowReferencePass::bindForLookup() const {
    glBindImageTexture(1, heads_.get(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32UI);
    const GLuint bindings[kShadowNodePools] = {10, 12, 13, 14};
    for (size_t i = 0; i < size_t(kShadowNodePools); ++i)
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, bindings[i], i < pools_.size() ? pools_[i].get() : unusedPool_.get());
}

}  // namespace hdhair::gl
