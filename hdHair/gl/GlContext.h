#pragma once
// A headless OpenGL 4.5 core context. hdHair never draws into a host's
// context: it owns one of these on its own render thread (GlRenderThread) and
// renders into framebuffer objects, so a surfaceless EGL context (the default)
// or an OSMesa context (the fallback) is all it needs.

#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

namespace hdhair::gl {

enum class GlBackend { Egl, OsMesa };

const char* toString(GlBackend backend);
// "egl" or "osmesa"; returns false for anything else.
bool parseGlBackend(const std::string& name, GlBackend* out);
// The backend named by HDHAIR_GL ("egl"/"osmesa"), or EGL when unset.
// Throws std::invalid_argument for an unknown value.
GlBackend defaultGlBackend();

// Thrown when no usable context can be made; the message lists what was tried.
class GlUnavailableError : public std::runtime_error {
public:
    explicit GlUnavailableError(const std::string& message) : std::runtime_error(message) {}
};

class GlContext {
public:
    virtual ~GlContext() = default;
    GlContext(const GlContext&) = delete;
    GlContext& operator=(const GlContext&) = delete;

    virtual GlBackend backend() const = 0;
    // GL_RENDERER and GL_VERSION, e.g. "llvmpipe (LLVM 15.0.6, 256 bits), 4.5 (Core Profile) Mesa 22.3.6".
    const std::string& description() const { return description_; }
    // Where the context was made: "EGL surfaceless (Mesa)", "EGL device 0
    // (NVIDIA H200, /dev/dri/renderD128)", "OSMesa".
    const std::string& origin() const { return origin_; }
    // One line when the context landed on a software renderer although a GPU
    // is present (SoftwareRenderer.h); "" otherwise.
    const std::string& softwareRendererWarning() const { return softwareRendererWarning_; }

protected:
    GlContext() = default;
    // Loads GL entry points through glad and checks for 4.5 core; throws
    // GlUnavailableError otherwise. Called by each backend once current.
    void loadFunctions(void* (*getProcAddress)(const char*), const std::string& what);
    void setOrigin(std::string origin) { origin_ = std::move(origin); }
    void setSoftwareRendererWarning(std::string warning) { softwareRendererWarning_ = std::move(warning); }

private:
    std::string description_, origin_, softwareRendererWarning_;
};

// Makes a context current on the calling thread. Throws GlUnavailableError.
std::unique_ptr<GlContext> createEglContext();
std::unique_ptr<GlContext> createOsMesaContext();
std::unique_ptr<GlContext> createGlContext(GlBackend backend);

}  // namespace hdhair::gl
