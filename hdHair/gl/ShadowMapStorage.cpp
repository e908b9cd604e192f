#include "hdHair/gl/ShadowMapStorage.h"

#include <array>
#include <string>

#include "hdHair/gl/GpuMemory.h"

namespace hdhair::gl {

namespace {

constexpr float kNoHair = 3.0e38f;  // HDHAIR_NO_HAIR in shaders/include/shadows.glsl

Texture arrayTexture(GLenum format, int resolution, int layers) {
    GLuint name = 0;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &name);
    glTextureStorage3D(name, 1, format, resolution, resolution, layers);
    recordTextureStorage(name, format, resolution, resolution, layers, 0, "shadowMaps");
    // Read with texelFetch only: z0-relative values cannot be filtered.
    glTextureParameteri(name, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(name, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return Texture(name);
}

}  // namespace

ShadowMapStorage::ShadowMapStorage() {
    GLuint name = 0;
    glCreateFramebuffers(1, &name);
    framebuffer_ = Framebuffer(name);
    ensure(1, 1, 1);
}

void ShadowMapStorage::ensure(int resolution, int layerTargets, int slots) {
    if (resolution == resolution_ && layerTargets == targets_ && slots == slots_) return;
    resolution_ = resolution;
    targets_ = layerTargets;
    slots_ = slots;
    allocate();
}

void ShadowMapStorage::allocate() {
    depths_ = arrayTexture(GL_R32F, resolution_, slots_);
    opacity_ = arrayTexture(GL_RGBA16F, resolution_, slots_ * targets_);
    meshDepths_ = arrayTexture(GL_R32F, resolution_, slots_);
    checkGlError(("allocating " + std::to_string(slots_) + " shadow maps of " + std::to_string(resolution_) + "x" +
                  std::to_string(resolution_) + " texels")
                     .c_str());
}

void ShadowMapStorage::bindDepthTarget(int slot) { bindNearestDepthTarget(depths_, slot); }

void ShadowMapStorage::bindMeshDepthTarget(int slot) { bindNearestDepthTarget(meshDepths_, slot); }

void ShadowMapStorage::bindNearestDepthTarget(const Texture& depths, int slot) {
    for (int i = 1; i < 8; ++i) glNamedFramebufferTexture(framebuffer_.get(), GLenum(GL_COLOR_ATTACHMENT0 + i), 0, 0);
    glNamedFramebufferTextureLayer(framebuffer_.get(), GL_COLOR_ATTACHMENT0, depths.get(), 0, slot);
    glNamedFramebufferDrawBuffer(framebuffer_.get(), GL_COLOR_ATTACHMENT0);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.get());
    glViewport(0, 0, resolution_, resolution_);
    const float none[4] = {kNoHair, 0.0f, 0.0f, 0.0f};
    glClearNamedFramebufferfv(framebuffer_.get(), GL_COLOR, 0, none);
    checkGlError("binding a shadow depth map");
}

void ShadowMapStorage::bindOpacityTargets(int slot) {
    std::array<GLenum, 8> buffers;
    buffers.fill(GL_NONE);
    for (int i = 0; i < 8; ++i) {
        if (i < targets_) {
            glNamedFramebufferTextureLayer(framebuffer_.get(), GLenum(GL_COLOR_ATTACHMENT0 + i), opacity_.get(), 0,
                                           slot * targets_ + i);
            buffers[size_t(i)] = GLenum(GL_COLOR_ATTACHMENT0 + i);
        } else {
            glNamedFramebufferTexture(framebuffer_.get(), GLenum(GL_COLOR_ATTACHMENT0 + i), 0, 0);
        }
    }
    glNamedFramebufferDrawBuffers(framebuffer_.get(), 8, buffers.data());
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.get());
    glViewport(0, 0, resolution_, resolution_);
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    for (int i = 0; i < targets_; ++i) glClearNamedFramebufferfv(framebuffer_.get(), GL_COLOR, i, zero);
    checkGlError("binding shadow opacity layers");
}

void ShadowMapStorage::bindForLookup() const {
    glBindTextureUnit(2, depths_.get());
    glBindTextureUnit(3, opacity_.get());
    glBindTextureUnit(4, meshDepths_.get());
}

}  // namespace hdhair::gl
