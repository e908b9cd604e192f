#include "hdHair/gl/RenderTarget.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "hdHair/gl/GpuMemory.h"

namespace hdhair::gl {

RenderTarget::RenderTarget(int width, int height, const RenderTargetImages& images)
    : width_(width), height_(height), images_(images) {
    // Checked before anything is allocated: the attachments are textures
    // drawn through a viewport, so all three limits apply, and a driver
    // asked for more may fail late or not at all (llvmpipe allocates).
    GLint renderbufferSize = 0, textureSize = 0, viewport[2] = {0, 0};
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &renderbufferSize);
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &textureSize);
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
    const GLint maxWidth = std::min({renderbufferSize, textureSize, viewport[0]});
    const GLint maxHeight = std::min({renderbufferSize, textureSize, viewport[1]});
    if (width <= 0 || height <= 0 || width > maxWidth || height > maxHeight)
        throw std::runtime_error("image size " + std::to_string(width) + "x" + std::to_string(height) +
                                 " is outside what the GL driver supports (1 to " + std::to_string(maxWidth) + "x" +
                                 std::to_string(maxHeight) +
                                 " pixels: GL_MAX_TEXTURE_SIZE, GL_MAX_RENDERBUFFER_SIZE, GL_MAX_VIEWPORT_DIMS)");
    create(draw_, images_.samples);
    if (images_.samples > 0) create(resolved_, 0);
    checkGlError(("creating the " + std::to_string(width) + "x" + std::to_string(height) + " render target").c_str());
}

std::array<GLenum, kOutputCount> RenderTarget::drawBuffers() const {
    // Outputs without an image are NONE: the strand shaders' writes to them
    // are discarded.
    std::array<GLenum, kOutputCount> buffers;
    buffers.fill(GL_NONE);
    buffers[kColorOutput] = GL_COLOR_ATTACHMENT0 + kColorOutput;
    for (int i = 0; images_.ids && i < 3; ++i)
        buffers[size_t(kFirstIdOutput + i)] = GLenum(GL_COLOR_ATTACHMENT0 + kFirstIdOutput + i);
    if (images_.nearestDepth) buffers[kNearestDepthOutput] = GL_COLOR_ATTACHMENT0 + kNearestDepthOutput;
    return buffers;
}

void RenderTarget::create(Attachments& a, int samples) {
    auto texture = [&](GLenum format) {
        GLuint name = 0;
        glCreateTextures(samples > 0 ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D, 1, &name);
        if (samples > 0) glTextureStorage2DMultisample(name, samples, format, width_, height_, GL_TRUE);
        else glTextureStorage2D(name, 1, format, width_, height_);
        // Its use is the one its owner names (FrameResources: frame or light batch).
        recordTextureStorage(name, format, width_, height_, 1, samples);
        return Texture(name);
    };
    GLuint name = 0;
    glCreateFramebuffers(1, &name);
    a.framebuffer = Framebuffer(name);
    auto attach = [&](GLenum attachment, Texture& image, GLenum format) {
        image = texture(format);
        glNamedFramebufferTexture(a.framebuffer.get(), attachment, image.get(), 0);
    };
    attach(GL_COLOR_ATTACHMENT0 + kColorOutput, a.color, GL_RGBA32F);
    attach(GL_DEPTH_ATTACHMENT, a.depth, GL_DEPTH_COMPONENT32F);
    for (int i = 0; images_.ids && i < 3; ++i)
        attach(GLenum(GL_COLOR_ATTACHMENT0 + kFirstIdOutput + i), a.ids[i], GL_R32I);
    if (images_.nearestDepth) attach(GL_COLOR_ATTACHMENT0 + kNearestDepthOutput, a.nearestDepth, GL_R32F);
    glNamedFramebufferDrawBuffers(a.framebuffer.get(), kOutputCount, drawBuffers().data());
    GLenum status = glCheckNamedFramebufferStatus(a.framebuffer.get(), GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("the GL driver cannot render to this framebuffer (" + std::to_string(samples) +
                                 " samples; status " + std::to_string(status) + ")");
}

void RenderTarget::bind() {
    GLuint framebuffer = draw_.framebuffer.get();
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    // Light batches may have left the framebuffer drawing colour only.
    glNamedFramebufferDrawBuffers(framebuffer, kOutputCount, drawBuffers().data());
    glViewport(0, 0, width_, height_);
}

void RenderTarget::bindAndClear(const glm::vec4& clearColor) {
    bind();
    GLuint framebuffer = draw_.framebuffer.get();
    glClearNamedFramebufferfv(framebuffer, GL_COLOR, kColorOutput, &clearColor[0]);
    const float farthest = 1.0f;
    glClearNamedFramebufferfv(framebuffer, GL_DEPTH, 0, &farthest);
    if (images_.ids) {
        const GLint none[4] = {-1, -1, -1, -1};
        for (GLint i = 0; i < 3; ++i) glClearNamedFramebufferiv(framebuffer, GL_COLOR, kFirstIdOutput + i, none);
    }
    if (images_.nearestDepth) {
        const float nothing[4] = {farthest, 0.0f, 0.0f, 0.0f};
        glClearNamedFramebufferfv(framebuffer, GL_COLOR, kNearestDepthOutput, nothing);
    }
}

void RenderTarget::resolve() {
    if (images_.samples == 0) return;
    const GLuint from = draw_.framebuffer.get(), to = resolved_.framebuffer.get();
    const std::array<GLenum, kOutputCount> buffers = drawBuffers();
    for (int i = 0; i < kOutputCount; ++i) {
        if (buffers[size_t(i)] == GL_NONE) continue;
        glNamedFramebufferReadBuffer(from, buffers[size_t(i)]);
        glNamedFramebufferDrawBuffer(to, buffers[size_t(i)]);
        glBlitNamedFramebuffer(from, to, 0, 0, width_, height_, 0, 0, width_, height_,
                               i == kColorOutput ? GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT : GL_COLOR_BUFFER_BIT,
                               GL_NEAREST);
    }
    glNamedFramebufferDrawBuffers(to, kOutputCount, buffers.data());
    checkGlError("resolving the multisampled frame");
}

GLuint RenderTarget::resolvedColorTexture() const {
    return images_.samples > 0 ? resolved_.color.get() : draw_.color.get();
}

GLuint RenderTarget::readFramebuffer() const {
    return images_.samples > 0 ? resolved_.framebuffer.get() : draw_.framebuffer.get();
}

void RenderTarget::bindResolvedColorForDrawing() {
    GLuint framebuffer = readFramebuffer();
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    std::array<GLenum, kOutputCount> colorOnly;
    colorOnly.fill(GL_NONE);
    colorOnly[kColorOutput] = GL_COLOR_ATTACHMENT0 + kColorOutput;
    glNamedFramebufferDrawBuffers(framebuffer, kOutputCount, colorOnly.data());
    glViewport(0, 0, width_, height_);
}


std::vector<float> RenderTarget::readColor() const {
    return readTopDown<float>(readFramebuffer(), GL_COLOR_ATTACHMENT0 + kColorOutput, GL_RGBA, GL_FLOAT, 4,
                                  width_, height_);
}

std::vector<float> RenderTarget::readDepth() const {
    if (images_.nearestDepth)
        return readTopDown<float>(readFramebuffer(), GL_COLOR_ATTACHMENT0 + kNearestDepthOutput, GL_RED,
                                      GL_FLOAT, 1, width_, height_);
    return readTopDown<float>(readFramebuffer(), GL_DEPTH_ATTACHMENT, GL_DEPTH_COMPONENT, GL_FLOAT, 1, width_,
                                  height_);
}

std::vector<int32_t> RenderTarget::readIds(int index) const {
    if (!images_.ids || index < 0 || index > 2)
        throw std::runtime_error("the render target has no id image " + std::to_string(index));
    return readTopDown<int32_t>(readFramebuffer(), GLenum(GL_COLOR_ATTACHMENT0 + kFirstIdOutput + index),
                                    GL_RED_INTEGER, GL_INT, 1, width_, height_);
}

}  // namespace hdhair::gl
