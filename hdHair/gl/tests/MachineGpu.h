#pragma once
// Whether the machine running a test has a GPU, found out here with raw EGL
// calls rather than through hdHair's own EglContext, so that tests of the
// software-renderer warning compare it with an independent answer: on a
// machine without a GPU (CI's llvmpipe) no warning may appear, on one with a
// GPU the context must land on it or warn.

#include <filesystem>
#include <string>

#include <EGL/egl.h>
#include <EGL/eglext.h>

namespace hdhair::gl::testsupport {

struct MachineGpu {
    bool nvidiaDeviceFile = false;
    int hardwareEglDevices = 0;  // enumerated devices without EGL_MESA_device_software
    bool present() const { return nvidiaDeviceFile || hardwareEglDevices > 0; }
};

inline MachineGpu probeMachineGpu() {
    MachineGpu gpu;
    std::error_code ignored;
    gpu.nvidiaDeviceFile = std::filesystem::exists("/dev/nvidia0", ignored);
    auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    auto queryString =
        reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (!queryDevices || !queryString || !queryDevices(16, devices, &count)) return gpu;
    for (EGLint i = 0; i < count; ++i) {
        const char* extensions = queryString(devices[i], EGL_EXTENSIONS);
        if (!extensions || std::string(" ").append(extensions).append(" ").find(" EGL_MESA_device_software ") ==
                               std::string::npos)
            gpu.hardwareEglDevices += 1;
    }
    return gpu;
}

}  // namespace hdhair::gl::testsupport
