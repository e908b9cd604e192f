// Headless EGL, the context made current with no surface (hdHair renders
// into FBOs). Displays are tried in this order:
//  1. hardware EGL devices (EGL_EXT_device_enumeration, EGL_EXT_platform_device):
//     a GPU's own driver, NVIDIA's included, which Mesa's platforms never reach.
//     Which of them, and in what order, EglDeviceChoice.h decides: every one
//     in enumeration order, or only the one HDHAIR_EGL_DEVICE names or the one
//     a Slurm task was given, so that farm tasks do not all share device 0;
//  2. Mesa's surfaceless platform: no display server and no device files
//     needed (a Mesa GPU driver through its render node, else llvmpipe);
//  3. Mesa's software EGL device (EGL_MESA_device_software);
//  4. the default display.
// When the context lands on a software renderer while a GPU is present, the
// context carries a one-line warning (SoftwareRenderer.h) that the renderer
// reports through Diagnostics.

#include <cstdlib>
#include <filesystem>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include "hdHair/gl/EglDeviceChoice.h"
#include "hdHair/gl/GlContext.h"
#include "hdHair/gl/SoftwareRenderer.h"

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
    void load(const std::string& what, const std::string& origin, const GpuEvidence& evidence) {
        loadFunctions(reinterpret_cast<void* (*)(const char*)>(&eglGetProcAddress), what);
        setOrigin(origin);
        setSoftwareRendererWarning(hdhair::gl::softwareRendererWarning(description(), evidence));
    }

private:
    EGLDisplay display_;
    EGLContext context_;
};

struct DisplayCandidate {
    std::string name;
    EGLDisplay display;
    bool hardware = false;  // an enumerated hardware device (its failures go into the warning)
    // What origin() says of a context made here: the name, or for a device
    // chosen as the task's GPU why it was (EglDeviceChoice::reason).
    std::string origin = name;
};

// "EGL device 1 (NVIDIA H200, /dev/dri/renderD129)": the index and what the
// device says of itself, where its extensions let it.
std::string describeDevice(PFNEGLQUERYDEVICESTRINGEXTPROC queryString, EGLDeviceEXT device, EGLint index,
                           const std::string& extensions) {
    std::string details;
    auto add = [&](EGLint name, const char* extension) {
        if (!queryString || extensions.find(extension) == std::string::npos) return;
        const char* value = queryString(device, name);
        if (value && *value) details += (details.empty() ? "" : ", ") + std::string(value);
    };
    add(EGL_RENDERER_EXT, "EGL_EXT_device_query_name");
    add(EGL_DRM_RENDER_NODE_FILE_EXT, "EGL_EXT_device_drm_render_node");
    if (details.find("/dev/") == std::string::npos) add(EGL_DRM_DEVICE_FILE_EXT, "EGL_EXT_device_drm");
    if (isSoftwareEglDevice(extensions)) details += (details.empty() ? "" : ", ") + std::string("software");
    return "EGL device " + std::to_string(index) + (details.empty() ? "" : " (" + details + ")");
}

// The device's CUDA ordinal (EGL_NV_device_cuda), which ties it to the GPU
// a Slurm task was given; none where the device or the query has none.
std::optional<int> cudaDevice(PFNEGLQUERYDEVICEATTRIBEXTPROC queryAttribute, EGLDeviceEXT device,
                              const std::string& extensions) {
    if (!queryAttribute || extensions.find("EGL_NV_device_cuda") == std::string::npos) return std::nullopt;
    EGLAttrib ordinal = -1;
    if (!queryAttribute(device, EGL_CUDA_DEVICE_NV, &ordinal) || ordinal < 0 ||
        ordinal > std::numeric_limits<int>::max())
        return std::nullopt;
    return static_cast<int>(ordinal);
}

std::vector<DisplayCandidate> candidateDisplays(std::vector<std::string>& tried, GpuEvidence& evidence) {
    std::vector<DisplayCandidate> hardware, surfaceless, software;
    auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (getPlatformDisplay) {
        auto queryDevices =
            reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
        auto queryString =
            reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
        auto queryAttribute =
            reinterpret_cast<PFNEGLQUERYDEVICEATTRIBEXTPROC>(eglGetProcAddress("eglQueryDeviceAttribEXT"));
        EGLDeviceEXT devices[16];
        EGLint deviceCount = 0;
        if (queryDevices && queryDevices(16, devices, &deviceCount)) {
            // What each device is first, then which hardware devices to open
            // (EglDeviceChoice.h): a GPU left out is not even opened, since
            // it may be another task's.
            std::vector<EglDeviceFacts> facts;
            for (EGLint i = 0; i < deviceCount; ++i) {
                const char* extensions = queryString ? queryString(devices[i], EGL_EXTENSIONS) : nullptr;
                const std::string deviceExtensions = extensions ? extensions : "";
                const bool isHardware = !isSoftwareEglDevice(deviceExtensions);
                facts.push_back({i, isHardware, cudaDevice(queryAttribute, devices[i], deviceExtensions),
                                 describeDevice(queryString, devices[i], i, deviceExtensions)});
                if (isHardware) evidence.hardwareDevices.push_back(facts.back().name);
            }
            EglDeviceChoice choice;
            try {
                choice = chooseEglDevices(facts, [](const char* name) { return std::getenv(name); });
            } catch (const std::invalid_argument& error) {
                throw GlUnavailableError(error.what());  // a device asked for by hand is not replaced
            }
            // The reason leads the list of what was tried, and explains the
            // software warning when the task's GPU was missing or failed.
            if (!choice.reason.empty()) {
                tried.push_back(choice.reason);
                if (!evidence.hardwareDevices.empty()) evidence.hardwareFailures.push_back(choice.reason);
            }
            auto open = [&](const EglDeviceFacts& device, std::vector<DisplayCandidate>& into) {
                EGLDisplay display = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[device.index], nullptr);
                if (display == EGL_NO_DISPLAY) {
                    tried.push_back(device.name + ": no display");
                    if (device.hardware) evidence.hardwareFailures.push_back(tried.back());
                    return false;
                }
                into.push_back({device.name, display, device.hardware});
                return true;
            };
            for (int index : choice.hardwareOrder) {
                if (!open(facts[static_cast<size_t>(index)], hardware) || choice.reason.empty()) continue;
                // A context there says why it is on that device (--verbose
                // prints the origin); the reason begins with the device's name.
                DisplayCandidate& chosen = hardware.back();
                chosen.origin = choice.reason.rfind(chosen.name, 0) == 0 ? choice.reason
                                                                         : chosen.name + "; " + choice.reason;
            }
            for (const EglDeviceFacts& device : facts)
                if (!device.hardware) open(device, software);
        } else {
            tried.push_back("EGL device platform: no devices");
        }
        EGLDisplay mesa = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (mesa != EGL_NO_DISPLAY) surfaceless.push_back({"EGL surfaceless (Mesa)", mesa});
        else tried.push_back("EGL surfaceless (Mesa): no display");
    } else {
        tried.push_back("eglGetPlatformDisplayEXT: not available");
    }
    std::vector<DisplayCandidate> displays = hardware;
    displays.insert(displays.end(), surfaceless.begin(), surfaceless.end());
    displays.insert(displays.end(), software.begin(), software.end());
    EGLDisplay fallback = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (fallback != EGL_NO_DISPLAY) displays.push_back({"EGL default display", fallback});
    return displays;
}

}  // namespace

std::unique_ptr<GlContext> createEglContext() {
    std::vector<std::string> tried;
    GpuEvidence evidence;
    // The NVIDIA kernel driver's device file: a GPU even when its EGL driver
    // is missing and no device is enumerated.
    std::error_code ignored;
    evidence.nvidiaDeviceFile = std::filesystem::exists("/dev/nvidia0", ignored);
    for (const DisplayCandidate& candidate : candidateDisplays(tried, evidence)) {
        // Each failure is also kept for the warning when it was a GPU's.
        auto fail = [&](const std::string& why) {
            tried.push_back(candidate.name + ": " + why);
            if (candidate.hardware) evidence.hardwareFailures.push_back(tried.back());
        };
        EGLint major = 0, minor = 0;
        if (!eglInitialize(candidate.display, &major, &minor)) {
            fail("eglInitialize failed (" + eglErrorName(eglGetError()) + ")");
            continue;
        }
        if (!eglBindAPI(EGL_OPENGL_API)) {
            fail("no desktop OpenGL API");
            eglTerminate(candidate.display);
            continue;
        }
        // A pbuffer-capable config first: EGL's default surface type is a
        // window, which device displays (NVIDIA's) have no configs for. Then
        // any OpenGL config; with EGL_KHR_no_config_context a config is
        // optional, so none is passed when the driver matches neither.
        const EGLint pbufferConfig[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                        EGL_NONE};
        const EGLint anyConfig[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
        EGLConfig config = nullptr;
        EGLint configCount = 0;
        if (!eglChooseConfig(candidate.display, pbufferConfig, &config, 1, &configCount) || configCount == 0)
            if (!eglChooseConfig(candidate.display, anyConfig, &config, 1, &configCount) || configCount == 0)
                config = nullptr;
        const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4,
                                            EGL_CONTEXT_MINOR_VERSION, 5,
                                            EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                            EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                            EGL_NONE};
        EGLContext context =
            eglCreateContext(candidate.display, config, EGL_NO_CONTEXT, contextAttributes);
        if (context == EGL_NO_CONTEXT) {
            fail("no OpenGL 4.5 core context (" + eglErrorName(eglGetError()) + ")");
            eglTerminate(candidate.display);
            continue;
        }
        if (!eglMakeCurrent(candidate.display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
            fail("eglMakeCurrent without a surface failed (" + eglErrorName(eglGetError()) + ")");
            eglDestroyContext(candidate.display, context);
            eglTerminate(candidate.display);
            continue;
        }
        auto result = std::make_unique<EglContext>(candidate.display, context);
        try {
            result->load(candidate.name, candidate.origin, evidence);
        } catch (const GlUnavailableError& error) {
            tried.push_back(error.what());
            if (candidate.hardware) evidence.hardwareFailures.push_back(error.what());
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
