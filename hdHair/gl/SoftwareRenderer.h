#pragma once
// Whether a GL context runs on a software rasterizer while the machine has a
// GPU it could have used. On a machine with an NVIDIA GPU and Mesa installed,
// Mesa's surfaceless EGL platform still gives llvmpipe: every frame then runs
// on the CPU, many times slower, with nothing else to tell the user. These
// are the decisions behind the one-line warning EglContext raises, kept free
// of EGL calls so that they can be tested on a machine without a GPU.

#include <string>
#include <vector>

namespace hdhair::gl {

// GL_RENDERER of a software rasterizer: Mesa's llvmpipe, softpipe and swrast
// ("Software Rasterizer"), and Google's SwiftShader. Case-insensitive.
bool isSoftwareRenderer(const std::string& glRenderer);

// An EGL device (EGL_EXT_device_enumeration) that is Mesa's software device:
// its extension string names EGL_MESA_device_software. Every other
// enumerated device is a hardware one (NVIDIA's, or a DRM device of Mesa's).
bool isSoftwareEglDevice(const std::string& deviceExtensions);

// What says that a GPU is present besides the context that was made.
struct GpuEvidence {
    bool nvidiaDeviceFile = false;             // /dev/nvidia0 exists (the NVIDIA kernel driver is loaded)
    std::vector<std::string> hardwareDevices;  // enumerated non-software EGL devices, described
    // Why each hardware device tried gave no context ("EGL device 0 (...):
    // eglInitialize failed (EGL_NOT_INITIALIZED)"), for the warning.
    std::vector<std::string> hardwareFailures;
};

bool gpuPresent(const GpuEvidence& evidence);

// The one-line warning for a context on `glRenderer`, or "" when there is
// none to give: the renderer is a hardware one, or no GPU is present.
std::string softwareRendererWarning(const std::string& glRenderer, const GpuEvidence& evidence);

}  // namespace hdhair::gl
