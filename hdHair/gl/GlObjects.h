#pragma once
// Owning handles for GL objects, created with direct state access (GL 4.5) so
// no binding leaks from one pass into another. Only valid on the GL thread.

#include <algorithm>
#include <cstddef>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <glad/gl.h>

namespace hdhair::gl {

// Move-only owner of one GL name; Deleter(GLuint) releases it.
template <void (*Deleter)(GLuint)>
class GlName {
public:
    GlName() = default;
    explicit GlName(GLuint name) : name_(name) {}
    ~GlName() { reset(); }
    GlName(GlName&& other) noexcept : name_(std::exchange(other.name_, 0)) {}
    GlName& operator=(GlName&& other) noexcept {
        if (this != &other) {
            reset();
            name_ = std::exchange(other.name_, 0);
        }
        return *this;
    }
    GlName(const GlName&) = delete;
    GlName& operator=(const GlName&) = delete;

    GLuint get() const { return name_; }
    explicit operator bool() const { return name_ != 0; }
    void reset() {
        if (name_) Deleter(name_);
        name_ = 0;
    }

private:
    GLuint name_ = 0;
};

void deleteBuffer(GLuint name);
void deleteVertexArray(GLuint name);
void deleteTexture(GLuint name);
void deleteFramebuffer(GLuint name);
void deleteProgram(GLuint name);
void deleteQuery(GLuint name);

using Buffer = GlName<deleteBuffer>;
using VertexArray = GlName<deleteVertexArray>;
using Texture = GlName<deleteTexture>;
using Framebuffer = GlName<deleteFramebuffer>;
using Program = GlName<deleteProgram>;
using Query = GlName<deleteQuery>;

// `use` names what the buffer is for in the GPU memory ledger (GpuMemory.h);
// nullptr: the GpuMemoryUse in effect, else "other".
Buffer createBuffer(const void* data, size_t bytes, GLbitfield flags = 0, const char* use = nullptr);
VertexArray createVertexArray();

// Compiles and links the named shaders from shaders/ (stage from the file
// extension). Throws std::runtime_error with the driver's log and the file.
// `overrides`: sources written at run time that replace embedded files of
// the same name (ShaderSources.h). `captured`: outputs of the last vertex
// stage recorded by transform feedback, interleaved in that order (tests
// read back what the tessellator made this way).
Program createProgram(const std::vector<std::string>& shaderNames,
                      const std::map<std::string, std::string>& overrides = {},
                      const std::vector<std::string>& captured = {});

// Throws std::runtime_error naming `what` if GL has recorded an error.
void checkGlError(const char* what);

// Reads `attachment` of `framebuffer` (or its depth, GL_DEPTH_ATTACHMENT):
// `channels` values of `type` a pixel, rows from the top of the image down
// (GL's run bottom-up).
template <typename Pixel>
std::vector<Pixel> readTopDown(GLuint framebuffer, GLenum attachment, GLenum format, GLenum type, int channels,
                               int width, int height) {
    std::vector<Pixel> pixels(size_t(width) * size_t(height) * size_t(channels));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
    if (attachment != GL_DEPTH_ATTACHMENT) glNamedFramebufferReadBuffer(framebuffer, attachment);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, format, type, pixels.data());
    checkGlError("reading back the image");
    const size_t rowSize = size_t(width) * size_t(channels);
    for (int y = 0; y < height / 2; ++y)
        std::swap_ranges(pixels.begin() + std::ptrdiff_t(size_t(y) * rowSize),
                         pixels.begin() + std::ptrdiff_t(size_t(y + 1) * rowSize),
                         pixels.begin() + std::ptrdiff_t(size_t(height - 1 - y) * rowSize));
    return pixels;
}

}  // namespace hdhair::gl
