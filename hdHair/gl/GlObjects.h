#pragma once
// Owning handles for GL objects, created with direct state access (GL 4.5) so
// no binding leaks from one pass into another. Only valid on the GL thread.

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

using Buffer = GlName<deleteBuffer>;
using VertexArray = GlName<deleteVertexArray>;
using Texture = GlName<deleteTexture>;
using Framebuffer = GlName<deleteFramebuffer>;
using Program = GlName<deleteProgram>;

Buffer createBuffer(const void* data, size_t bytes, GLbitfield flags = 0);
VertexArray createVertexArray();

// Compiles and links the named shaders from shaders/ (stage from the file
// extension). Throws std::runtime_error with the driver's log and the file.
Program createProgram(const std::vector<std::string>& shaderNames);

// Throws std::runtime_error naming `what` if GL has recorded an error.
void checkGlError(const char* what);

}  // namespace hdhair::gl
