#include "hdHair/gl/SoftwareRenderer.h"

#include <algorithm>
#include <cctype>
#include <sstream>

namespace hdhair::gl {

namespace {

std::string lowercase(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return text;
}

}  // namespace

bool isSoftwareRenderer(const std::string& glRenderer) {
    const std::string renderer = lowercase(glRenderer);
    for (const char* name : {"llvmpipe", "softpipe", "swrast", "software rasterizer", "swiftshader"})
        if (renderer.find(name) != std::string::npos) return true;
    return false;
}

bool isSoftwareEglDevice(const std::string& deviceExtensions) {
    // A whole token: no extension merely starts with this name today, but a
    // substring test would misread one that did.
    std::istringstream tokens(deviceExtensions);
    std::string token;
    while (tokens >> token)
        if (token == "EGL_MESA_device_software") return true;
    return false;
}

bool gpuPresent(const GpuEvidence& evidence) {
    return evidence.nvidiaDeviceFile || !evidence.hardwareDevices.empty();
}

std::string softwareRendererWarning(const std::string& glRenderer, const GpuEvidence& evidence) {
    if (!isSoftwareRenderer(glRenderer) || !gpuPresent(evidence)) return "";
    std::string found;
    if (evidence.nvidiaDeviceFile) found = "/dev/nvidia0";
    for (const std::string& device : evidence.hardwareDevices) found += (found.empty() ? "" : ", ") + device;
    std::string message = "OpenGL runs on the software renderer '" + glRenderer + "' although a GPU is present (" +
                          found + "); every frame is drawn on the CPU, many times slower: ";
    if (evidence.hardwareDevices.empty()) {
        message += "EGL enumerates no device of it: install its EGL driver (for NVIDIA, the driver's libEGL_nvidia with "
                   "its glvnd vendor file 10_nvidia.json) and check the permissions of /dev/nvidia*";
    } else {
        message += "no OpenGL 4.5 core context could be made on it (";
        for (size_t i = 0; i < evidence.hardwareFailures.size(); ++i)
            message += (i ? "; " : "") + evidence.hardwareFailures[i];
        if (evidence.hardwareFailures.empty()) message += "its own EGL device gave this software context";
        message += ")";
    }
    return message;
}

}  // namespace hdhair::gl
