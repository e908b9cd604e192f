// Headless EGL: Mesa's surfaceless platform first (no display server, no
// device files needed: llvmpipe on a CPU machine), then the EGL device
// platform (vendor drivers such as NVIDIA's), then the default display.
// The context is made current with no surface; hdHair renders into FBOs.

#include <string>
#include <vector>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include "hdHair/gl/GlContext.h"

namespace hdhair::gl {
namespace {

std::string eglErrorName(EGLint error) {
    switch (error) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    default: return "EGL error " + std::to_string(error);
    }
}

class EglContext final : public GlContext {
public:
    EglContext(EGLDisplay display, EGLContext context) : display_(display), context_(context) {}
    ~EglContext() override {
        eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(display_, context_);
        eglTerminate(display_);
    }
    GlBackend backend() const override { return GlBackend::Egl; }
    void load(const std::string& what) {
        loadFunctions(reinterpret_cast<void* (*)(const char*)>(&eglGetProcAddress), what);
    }

private:
    EGLDisplay display_;
    EGLContext context_;
};

struct DisplayCandidate {
    std::string name;
    EGLDisplay display;
};

std::vector<DisplayCandidate> candidateDisplays(std::vector<std::string>& tried) {
    std::vector<DisplayCandidate> displays;
    auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (getPlatformDisplay) {
        EGLDisplay surfaceless =
            getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (surfaceless != EGL_NO_DISPLAY) displays.push_back({"EGL surfaceless (Mesa)", surfaceless});
        else tried.push_back("EGL surfaceless (Mesa): no display");

        auto queryDevices =
            reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
        EGLDeviceEXT devices[8];
        EGLint deviceCount = 0;
        if (queryDevices && queryDevices(8, devices, &deviceCount)) {
            for (EGLint i = 0; i < deviceCount; ++i) {
                EGLDisplay display = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
                if (display != EGL_NO_DISPLAY)
                    displays.push_back({"EGL device " + std::to_string(i), display});
            }
        } else {
            tried.push_back("EGL device platform: no devices");
        }
    } else {
        tried.push_back("eglGetPlatformDisplayEXT: not available");
    }
    EGLDisplay fallback = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (fallback != EGL_NO_DISPLAY) displays.push_back({"EGL default display", fallback});
    return displays;
}

}  // namespace

std::unique_ptr<GlContext> createEglContext() {
    std::vector<std::string> tried;
    for (const DisplayCandidate& candidate : candidateDisplays(tried)) {
        EGLint major = 0, minor = 0;
        if (!eglInitialize(candidate.display, &major, &minor)) {
            tried.push_back(candidate.name + ": eglInitialize failed (" + eglErrorName(eglGetError()) + ")");
            continue;
        }
        if (!eglBindAPI(EGL_OPENGL_API)) {
            tried.push_back(candidate.name + ": no desktop OpenGL API");
            eglTerminate(candidate.display);
            continue;
        }
        const EGLint configAttributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
        EGLConfig config = nullptr;
        EGLint configCount = 0;
        // With EGL_KHR_no_config_context a config is optional; ask for one anyway
        // and pass none if the driver has no matching config.
        if (!eglChooseConfig(candidate.display, configAttributes, &config, 1, &configCount) ||
            configCount == 0)
            config = nullptr;
        const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4,
                                            EGL_CONTEXT_MINOR_VERSION, 5,
                                            EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                            EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                            EGL_NONE};
        EGLContext context =
            eglCreateContext(candidate.display, config, EGL_NO_CONTEXT, contextAttributes);
        if (context == EGL_NO_CONTEXT) {
            tried.push_back(candidate.name + ": no OpenGL 4.5 core context (" +
                            eglErrorName(eglGetError()) + ")");
            eglTerminate(candidate.display);
            continue;
        }
        if (!eglMakeCurrent(candidate.display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
            tried.push_back(candidate.name + ": eglMakeCurrent without a surface failed (" +
                            eglErrorName(eglGetError()) + ")");
            eglDestroyContext(candidate.display, context);
            eglTerminate(candidate.display);
            continue;
        }
        auto result = std::make_unique<EglContext>(candidate.display, context);
        try {
            result->load(candidate.name);
        } catch (const GlUnavailableError& error) {
            tried.push_back(error.what());
            continue;
        }
        return result;
    }
    // One line, so command-line tools can print it as their one-line reason.
    std::string message = "no usable OpenGL 4.5 context through EGL (tried: ";
    for (size_t i = 0; i < tried.size(); ++i) message += (i ? "; " : "") + tried[i];
    message += "); try --gl osmesa, or install Mesa's EGL driver (libegl-mesa0, libgl1-mesa-dri)";
    throw GlUnavailableError(message);
}

}  // namespace hdhair::gl
