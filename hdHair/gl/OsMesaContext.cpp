// OSMesa fallback: Mesa's off-screen context, rendering with llvmpipe into
// client memory. hdHair binds a 1x1 buffer only to make the context current;
// every pass renders into its own framebuffer objects.

#include <string>
#include <vector>

#include <GL/osmesa.h>

#include "hdHair/gl/GlContext.h"

namespace hdhair::gl {
namespace {

class OsMesaContext final : public GlContext {
public:
    explicit OsMesaContext(OSMesaContext context) : context_(context), pixel_(4, 0) {}
    ~OsMesaContext() override { OSMesaDestroyContext(context_); }
    GlBackend backend() const override { return GlBackend::OsMesa; }

    bool makeCurrent() {
        return OSMesaMakeCurrent(context_, pixel_.data(), 0x1401 /* GL_UNSIGNED_BYTE */, 1, 1);
    }
    void load() {
        loadFunctions(reinterpret_cast<void* (*)(const char*)>(&OSMesaGetProcAddress), "OSMesa");
        // OSMesa is always a software renderer, and asked for by name
        // (--gl osmesa, HDHAIR_GL): no warning that a GPU goes unused.
        setOrigin("OSMesa");
    }

private:
    OSMesaContext context_;
    std::vector<unsigned char> pixel_;
};

}  // namespace

std::unique_ptr<GlContext> createOsMesaContext() {
    const int attributes[] = {OSMESA_FORMAT, OSMESA_RGBA,
                              OSMESA_DEPTH_BITS, 0,
                              OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                              OSMESA_CONTEXT_MAJOR_VERSION, 4,
                              OSMESA_CONTEXT_MINOR_VERSION, 5,
                              0};
    OSMesaContext context = OSMesaCreateContextAttribs(attributes, nullptr);
    if (!context)
        throw GlUnavailableError(
            "no usable OpenGL 4.5 context through OSMesa: OSMesaCreateContextAttribs failed "
            "(install libosmesa6, or use --gl egl)");
    auto result = std::make_unique<OsMesaContext>(context);
    if (!result->makeCurrent())
        throw GlUnavailableError("no usable OpenGL context through OSMesa: OSMesaMakeCurrent failed");
    result->load();
    return result;
}

}  // namespace hdhair::gl
