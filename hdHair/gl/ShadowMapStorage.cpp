#include "hdHair/gl/ShadowMapStorage.h"

#include <array>
#include <stdexcept>
#include <string>

#include "hdHair/gl/GpuMemory.h"

namespace hdhair::gl {

namespace {

constexpr float kNoHair = 3.0e38f;  // HDHAIR_NO_HAIR in shaders/include/shadows.glsl

// The levels of a full mip chain down to 1 × 1.
int fullMipLevels(int resolution) {
    int levels = 1;
    while ((resolution >> levels) > 0) ++levels;
    return levels;
}

Texture arrayTexture(GLenum format, int resolution, int layers, int levels = 1) {
    GLuint name = 0;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &name);
    glTextureStorage3D(name, levels, format, resolution, resolution, layers);
    recordTextureStorage(name, format, resolution, resolution, layers, 0, "shadowMaps", levels);
    // The ordinary lookup reads with texelFetch: z0-relative values cannot be
    // filtered. The mip chain (opacity only) is read with textureLod by SRBF
    // lights, which average layers across texels on purpose (Ren et al. §5).
    glTextureParameteri(name, GL_TEXTURE_MIN_FILTER, levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_NEAREST);
    glTextureParameteri(name, GL_TEXTURE_MAG_FILTER, levels > 1 ? GL_LINEAR : GL_NEAREST);
    glTextureParameteri(name, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(name, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return Texture(name);
}

}  // namespace

ShadowMapStorage::ShadowMapStorage() {
    GLuint name = 0;
    glCreateFramebuffers(1, &name);
    framebuffer_ = Framebuffer(name);
    ensure(1, 1, 1);
}

void ShadowMapStorage::ensure(int resolution, int layerTargets, int slots, bool opacityMipmaps) {
    if (resolution == resolution_ && layerTargets == targets_ && slots == slots_ && opacityMipmaps == opacityMipmaps_)
        return;
    resolution_ = resolution;
    targets_ = layerTargets;
    slots_ = slots;
    opacityMipmaps_ = opacityMipmaps;
    allocate();
}

void ShadowMapStorage::generateOpacityMipmaps() {
    if (!opacityMipmaps_) throw std::logic_error("shadow maps: opacity mipmaps asked for but not allocated");
    glGenerateTextureMipmap(opacity_.get());
    checkGlError("averaging the shadow maps' opacity layers into mipmaps");
}

void ShadowMapStorage::allocate() {
    depths_ = arrayTexture(GL_R32F, resolution_, slots_);
    opacity_ = arrayTexture(GL_RGBA16F, resolution_, slots_ * targets_, opacityMipmaps_ ? fullMipLevels(resolution_) : 1);
    meshDepths_ = arrayTexture(GL_R32F, resolution_, slots_);
    checkGlError(("allocating " + std::to_string(slots_) + " shadow maps of " + std::to_string(resolution_) + "x" +
                  std::to_string(resolution_) + " texels")
                     .c_str());
}

void ShadowMapStorage::bindDepthTarget(int slot) { bindNearestDepthTarget(depths_, slot); }

void ShadowMapStorage::clearHairDepth(int slot) {
    const float none = kNoHair;
    glClearTexSubImage(depths_.get(), 0, 0, 0, slot, resolution_, resolution_, 1, GL_RED, GL_FLOAT, &none);
    checkGlError("clearing a shadow depth map");
}

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
