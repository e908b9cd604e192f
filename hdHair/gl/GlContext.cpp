#include "hdHair/gl/GlContext.h"

#include <cstdlib>

#include <glad/gl.h>

namespace hdhair::gl {

const char* toString(GlBackend backend) { return backend == GlBackend::Egl ? "egl" : "osmesa"; }

bool parseGlBackend(const std::string& name, GlBackend* out) {
    if (name == "egl") *out = GlBackend::Egl;
    else if (name == "osmesa") *out = GlBackend::OsMesa;
    else return false;
    return true;
}

GlBackend defaultGlBackend() {
    const char* env = std::getenv("HDHAIR_GL");
    if (!env || !*env) return GlBackend::Egl;
    GlBackend backend;
    if (!parseGlBackend(env, &backend))
        throw std::invalid_argument(std::string("HDHAIR_GL='") + env +
                                    "' is not a GL backend; use 'egl' or 'osmesa'");
    return backend;
}

void GlContext::loadFunctions(void* (*getProcAddress)(const char*), const std::string& what) {
    // glad2 wants a GLADloadfunc (void (*)(void) returning); both EGL's and
    // OSMesa's lookups return any entry point, core ones included.
    int version = gladLoadGL(reinterpret_cast<GLADloadfunc>(getProcAddress));
    if (version == 0) throw GlUnavailableError(what + ": could not load OpenGL entry points");
    int major = GLAD_VERSION_MAJOR(version), minor = GLAD_VERSION_MINOR(version);
    const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const char* versionString = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    description_ = std::string(renderer ? renderer : "?") + ", " + (versionString ? versionString : "?");
    if (major < 4 || (major == 4 && minor < 5))
        throw GlUnavailableError(what + ": OpenGL 4.5 core is required, the context offers " +
                                 description_);
}

std::unique_ptr<GlContext> createGlContext(GlBackend backend) {
    return backend == GlBackend::Egl ? createEglContext() : createOsMesaContext();
}

}  // namespace hdhair::gl
