#include "hdHair/gl/RenderTarget.h"

#include <stdexcept>
#include <string>

namespace hdhair::gl {

RenderTarget::RenderTarget(int width, int height, bool withIds)
    : width_(width), height_(height), withIds_(withIds) {
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxSize);
    if (width <= 0 || height <= 0 || width > maxSize || height > maxSize)
        throw std::runtime_error("image size " + std::to_string(width) + "x" + std::to_string(height) +
                                 " is outside what the GL driver supports (1 to " +
                                 std::to_string(maxSize) + " pixels a side)");
    GLuint name = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &name);
    color_ = Texture(name);
    glTextureStorage2D(color_.get(), 1, GL_RGBA32F, width, height);
    glCreateTextures(GL_TEXTURE_2D, 1, &name);
    depth_ = Texture(name);
    glTextureStorage2D(depth_.get(), 1, GL_DEPTH_COMPONENT32F, width, height);
    glCreateFramebuffers(1, &name);
    framebuffer_ = Framebuffer(name);
    glNamedFramebufferTexture(framebuffer_.get(), GL_COLOR_ATTACHMENT0, color_.get(), 0);
    glNamedFramebufferTexture(framebuffer_.get(), GL_DEPTH_ATTACHMENT, depth_.get(), 0);
    // The strand shaders write ids to outputs 1-3; without id images those
    // draw buffers are NONE and the writes are discarded.
    GLenum drawBuffers[4] = {GL_COLOR_ATTACHMENT0, GL_NONE, GL_NONE, GL_NONE};
    if (withIds_) {
        for (int i = 0; i < 3; ++i) {
            glCreateTextures(GL_TEXTURE_2D, 1, &name);
            ids_[i] = Texture(name);
            glTextureStorage2D(ids_[i].get(), 1, GL_R32I, width, height);
            GLenum attachment = GLenum(GL_COLOR_ATTACHMENT1 + i);
            glNamedFramebufferTexture(framebuffer_.get(), attachment, ids_[i].get(), 0);
            drawBuffers[i + 1] = attachment;
        }
    }
    glNamedFramebufferDrawBuffers(framebuffer_.get(), 4, drawBuffers);
    GLenum status = glCheckNamedFramebufferStatus(framebuffer_.get(), GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("the GL driver cannot render to an RGBA32F framebuffer (status " +
                                 std::to_string(status) + ")");
    checkGlError("creating the render target");
}

void RenderTarget::bindAndClear(const glm::vec4& clearColor) {
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.get());
    glViewport(0, 0, width_, height_);
    glClearNamedFramebufferfv(framebuffer_.get(), GL_COLOR, 0, &clearColor[0]);
    const float clearDepth = 1.0f;
    glClearNamedFramebufferfv(framebuffer_.get(), GL_DEPTH, 0, &clearDepth);
    if (withIds_) {
        const GLint none[4] = {-1, -1, -1, -1};
        for (GLint i = 1; i <= 3; ++i) glClearNamedFramebufferiv(framebuffer_.get(), GL_COLOR, i, none);
    }
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
    return readRowsTopDown<float>(framebuffer_.get(), GL_COLOR_ATTACHMENT0, GL_RGBA, GL_FLOAT, 4, width_, height_);
}

std::vector<float> RenderTarget::readDepth() const {
    return readRowsTopDown<float>(framebuffer_.get(), GL_DEPTH_ATTACHMENT, GL_DEPTH_COMPONENT, GL_FLOAT, 1, width_,
                                  height_);
}

std::vector<int32_t> RenderTarget::readIds(int index) const {
    if (!withIds_ || index < 0 || index > 2) throw std::runtime_error("the render target has no id image " +
                                                                      std::to_string(index));
    return readRowsTopDown<int32_t>(framebuffer_.get(), GLenum(GL_COLOR_ATTACHMENT1 + index), GL_RED_INTEGER, GL_INT,
                                    1, width_, height_);
}

}  // namespace hdhair::gl
