#include "hdHair/gl/RenderTarget.h"

#include <stdexcept>
#include <string>

namespace hdhair::gl {

RenderTarget::RenderTarget(int width, int height, bool withIds, int samples)
    : width_(width), height_(height), withIds_(withIds), samples_(samples) {
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxSize);
    if (width <= 0 || height <= 0 || width > maxSize || height > maxSize)
        throw std::runtime_error("image size " + std::to_string(width) + "x" + std::to_string(height) +
                                 " is outside what the GL driver supports (1 to " + std::to_string(maxSize) +
                                 " pixels a side)");
    create(draw_, samples_);
    if (samples_ > 0) create(resolved_, 0);
    checkGlError("creating the render target");
}

void RenderTarget::create(Attachments& a, int samples) {
    auto texture = [&](GLenum format) {
        GLuint name = 0;
        glCreateTextures(samples > 0 ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D, 1, &name);
        if (samples > 0) glTextureStorage2DMultisample(name, samples, format, width_, height_, GL_TRUE);
        else glTextureStorage2D(name, 1, format, width_, height_);
        return Texture(name);
    };
    a.color = texture(GL_RGBA32F);
    a.depth = texture(GL_DEPTH_COMPONENT32F);
    GLuint name = 0;
    glCreateFramebuffers(1, &name);
    a.framebuffer = Framebuffer(name);
    glNamedFramebufferTexture(a.framebuffer.get(), GL_COLOR_ATTACHMENT0, a.color.get(), 0);
    glNamedFramebufferTexture(a.framebuffer.get(), GL_DEPTH_ATTACHMENT, a.depth.get(), 0);
    // The strand shaders write ids to outputs 1-3; without id images those
    // draw buffers are NONE and the writes are discarded.
    GLenum drawBuffers[4] = {GL_COLOR_ATTACHMENT0, GL_NONE, GL_NONE, GL_NONE};
    if (withIds_) {
        for (int i = 0; i < 3; ++i) {
            a.ids[i] = texture(GL_R32I);
            GLenum attachment = GLenum(GL_COLOR_ATTACHMENT1 + i);
            glNamedFramebufferTexture(a.framebuffer.get(), attachment, a.ids[i].get(), 0);
            drawBuffers[i + 1] = attachment;
        }
    }
    glNamedFramebufferDrawBuffers(a.framebuffer.get(), 4, drawBuffers);
    GLenum status = glCheckNamedFramebufferStatus(a.framebuffer.get(), GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("the GL driver cannot render to this framebuffer (" + std::to_string(samples) +
                                 " samples; status " + std::to_string(status) + ")");
}

void RenderTarget::bindAndClear(const glm::vec4& clearColor) {
    GLuint framebuffer = draw_.framebuffer.get();
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    // Light batches may have left the framebuffer drawing colour only.
    GLenum drawBuffers[4] = {GL_COLOR_ATTACHMENT0, GL_NONE, GL_NONE, GL_NONE};
    for (int i = 1; withIds_ && i < 4; ++i) drawBuffers[i] = GLenum(GL_COLOR_ATTACHMENT0 + i);
    glNamedFramebufferDrawBuffers(framebuffer, 4, drawBuffers);
    glViewport(0, 0, width_, height_);
    glClearNamedFramebufferfv(framebuffer, GL_COLOR, 0, &clearColor[0]);
    const float clearDepth = 1.0f;
    glClearNamedFramebufferfv(framebuffer, GL_DEPTH, 0, &clearDepth);
    if (withIds_) {
        const GLint none[4] = {-1, -1, -1, -1};
        for (GLint i = 1; i <= 3; ++i) glClearNamedFramebufferiv(framebuffer, GL_COLOR, i, none);
    }
}

void RenderTarget::resolve() {
    if (samples_ == 0) return;
    const GLuint from = draw_.framebuffer.get(), to = resolved_.framebuffer.get();
    for (int i = 0; i < (withIds_ ? 4 : 1); ++i) {
        GLenum attachment = GLenum(GL_COLOR_ATTACHMENT0 + i);
        glNamedFramebufferReadBuffer(from, attachment);
        glNamedFramebufferDrawBuffer(to, attachment);
        glBlitNamedFramebuffer(from, to, 0, 0, width_, height_, 0, 0, width_, height_,
                               i == 0 ? GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT : GL_COLOR_BUFFER_BIT, GL_NEAREST);
    }
    GLenum drawBuffers[4] = {GL_COLOR_ATTACHMENT0, GL_NONE, GL_NONE, GL_NONE};
    for (int i = 1; withIds_ && i < 4; ++i) drawBuffers[i] = GLenum(GL_COLOR_ATTACHMENT0 + i);
    glNamedFramebufferDrawBuffers(to, 4, drawBuffers);
    checkGlError("resolving the multisampled frame");
}

GLuint RenderTarget::resolvedColorTexture() const {
    return samples_ > 0 ? resolved_.color.get() : draw_.color.get();
}

void RenderTarget::bindResolvedColorForDrawing() {
    GLuint framebuffer = samples_ > 0 ? resolved_.framebuffer.get() : draw_.framebuffer.get();
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    const GLenum colorOnly[4] = {GL_COLOR_ATTACHMENT0, GL_NONE, GL_NONE, GL_NONE};
    glNamedFramebufferDrawBuffers(framebuffer, 4, colorOnly);
    glViewport(0, 0, width_, height_);
}

namespace {

// GL's rows run bottom-up; images are stored top-down.
template <typename Pixel>
std::vector<Pixel> readRowsTopDown(GLuint framebuffer, GLenum attachment, GLenum format, GLenum type,
                                   int channels, int width, int height) {
    std::vector<Pixel> pixels(size_t(width) * size_t(height) * size_t(channels));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
    if (attachment != GL_DEPTH_ATTACHMENT) glNamedFramebufferReadBuffer(framebuffer, attachment);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, format, type, pixels.data());
    checkGlError("reading back the image");
    size_t rowSize = size_t(width) * size_t(channels);
    for (int y = 0; y < height / 2; ++y)
        std::swap_ranges(pixels.begin() + std::ptrdiff_t(size_t(y) * rowSize),
                         pixels.begin() + std::ptrdiff_t(size_t(y + 1) * rowSize),
                         pixels.begin() + std::ptrdiff_t(size_t(height - 1 - y) * rowSize));
    return pixels;
}

}  // namespace

std::vector<float> RenderTarget::readColor() const {
    GLuint framebuffer = samples_ > 0 ? resolved_.framebuffer.get() : draw_.framebuffer.get();
    return readRowsTopDown<float>(framebuffer, GL_COLOR_ATTACHMENT0, GL_RGBA, GL_FLOAT, 4, width_, height_);
}

std::vector<float> RenderTarget::readDepth() const {
    GLuint framebuffer = samples_ > 0 ? resolved_.framebuffer.get() : draw_.framebuffer.get();
    return readRowsTopDown<float>(framebuffer, GL_DEPTH_ATTACHMENT, GL_DEPTH_COMPONENT, GL_FLOAT, 1, width_, height_);
}

std::vector<int32_t> RenderTarget::readIds(int index) const {
    if (!withIds_ || index < 0 || index > 2)
        throw std::runtime_error("the render target has no id image " + std::to_string(index));
    GLuint framebuffer = samples_ > 0 ? resolved_.framebuffer.get() : draw_.framebuffer.get();
    return readRowsTopDown<int32_t>(framebuffer, GLenum(GL_COLOR_ATTACHMENT1 + index), GL_RED_INTEGER, GL_INT, 1,
                                    width_, height_);
}

}  // namespace hdhair::gl
