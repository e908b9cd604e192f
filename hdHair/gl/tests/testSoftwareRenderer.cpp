// The software-renderer warning (hdHair/gl/SoftwareRenderer.h): which
// renderer strings and EGL devices are software, when a GPU counts as
// present, the warning's one line, and what the EGL context on this machine
// chose and reported.

#include <string>

#include <gtest/gtest.h>

#include "hdHair/gl/GlRenderThread.h"
#include "hdHair/gl/SoftwareRenderer.h"
#include "hdHair/gl/tests/MachineGpu.h"

using namespace hdhair::gl;

TEST(SoftwareRenderer, RecognisesMesaAndOtherSoftwareRasterizers) {
    EXPECT_TRUE(isSoftwareRenderer("llvmpipe (LLVM 15.0.6, 256 bits)"));
    EXPECT_TRUE(isSoftwareRenderer("softpipe"));
    EXPECT_TRUE(isSoftwareRenderer("Software Rasterizer"));  // Mesa's swrast
    EXPECT_TRUE(isSoftwareRenderer("Gallium 0.4 on llvmpipe (LLVM 3.4, 128 bits)"));
    EXPECT_TRUE(isSoftwareRenderer("Google SwiftShader"));
    EXPECT_TRUE(isSoftwareRenderer("LLVMPIPE"));
}

TEST(SoftwareRenderer, HardwareRenderersAreNotSoftware) {
    EXPECT_FALSE(isSoftwareRenderer("NVIDIA H200/PCIe/SSE2"));
    // radeonsi compiles shaders with LLVM: "LLVM" alone is no software sign.
    EXPECT_FALSE(isSoftwareRenderer("AMD Radeon RX 7900 XTX (radeonsi, navi31, LLVM 15.0.7, DRM 3.54, 6.5.0)"));
    EXPECT_FALSE(isSoftwareRenderer("Mesa Intel(R) UHD Graphics 620 (KBL GT2)"));
    EXPECT_FALSE(isSoftwareRenderer(""));
}

TEST(SoftwareRenderer, OnlyMesasSoftwareDeviceIsASoftwareEglDevice) {
    // Mesa 22.3's software device, as enumerated on the CI machine.
    EXPECT_TRUE(isSoftwareEglDevice("EGL_MESA_device_software EGL_EXT_device_drm_render_node"));
    EXPECT_TRUE(isSoftwareEglDevice("EGL_EXT_device_drm_render_node EGL_MESA_device_software"));
    // NVIDIA's device and a Mesa DRM device.
    EXPECT_FALSE(isSoftwareEglDevice("EGL_NV_device_cuda EGL_EXT_device_drm EGL_EXT_device_drm_render_node "
                                     "EGL_EXT_device_query_name EGL_EXT_device_persistent_id"));
    EXPECT_FALSE(isSoftwareEglDevice("EGL_EXT_device_drm EGL_EXT_device_drm_render_node"));
    EXPECT_FALSE(isSoftwareEglDevice("EGL_MESA_device_software_2"));  // a whole token only
    EXPECT_FALSE(isSoftwareEglDevice(""));
}

TEST(SoftwareRenderer, AGpuIsPresentWithTheNvidiaDeviceFileOrAHardwareEglDevice) {
    EXPECT_FALSE(gpuPresent(GpuEvidence{}));
    GpuEvidence file;
    file.nvidiaDeviceFile = true;
    EXPECT_TRUE(gpuPresent(file));
    GpuEvidence device;
    device.hardwareDevices = {"EGL device 0 (NVIDIA H200, /dev/dri/renderD128)"};
    EXPECT_TRUE(gpuPresent(device));
}

TEST(SoftwareRenderer, WarnsInOneLineNamingTheRendererOnlyWhenAGpuGoesUnused) {
    const std::string llvmpipe = "llvmpipe (LLVM 15.0.6, 256 bits)";
    EXPECT_EQ(softwareRendererWarning(llvmpipe, GpuEvidence{}), "");  // no GPU: nothing to say

    GpuEvidence driverMissing;
    driverMissing.nvidiaDeviceFile = true;
    const std::string missing = softwareRendererWarning(llvmpipe, driverMissing);
    EXPECT_NE(missing.find("'" + llvmpipe + "'"), std::string::npos) << missing;
    EXPECT_NE(missing.find("/dev/nvidia0"), std::string::npos) << missing;
    EXPECT_NE(missing.find("EGL enumerates no device"), std::string::npos) << missing;
    EXPECT_EQ(missing.find('\n'), std::string::npos) << missing;

    GpuEvidence contextFailed;
    contextFailed.hardwareDevices = {"EGL device 0 (NVIDIA H200)"};
    contextFailed.hardwareFailures = {"EGL device 0 (NVIDIA H200): eglInitialize failed (EGL_NOT_INITIALIZED)"};
    const std::string failed = softwareRendererWarning(llvmpipe, contextFailed);
    EXPECT_NE(failed.find("EGL device 0 (NVIDIA H200): eglInitialize failed (EGL_NOT_INITIALIZED)"), std::string::npos)
        << failed;
    EXPECT_EQ(failed.find('\n'), std::string::npos) << failed;

    EXPECT_EQ(softwareRendererWarning("NVIDIA H200/PCIe/SSE2", contextFailed), "");  // on the GPU: fine
}

// On this machine: the EGL context prefers a hardware device when EGL
// enumerates one, else Mesa's surfaceless platform, and warns exactly when it
// ends up on a software renderer while a GPU is present. Without a GPU (the
// CI machine) that means surfaceless llvmpipe and no warning.
TEST(SoftwareRenderer, TheEglContextHereChoosesAsThisMachineCallsFor) {
    const testsupport::MachineGpu gpu = testsupport::probeMachineGpu();
    GlRenderThread thread(GlBackend::Egl);
    const std::string& origin = thread.contextOrigin();
    if (gpu.hardwareEglDevices > 0) {
        EXPECT_EQ(origin.rfind("EGL device ", 0), 0u) << origin;
        EXPECT_EQ(origin.find("software"), std::string::npos) << origin;
    } else {
        EXPECT_EQ(origin, "EGL surfaceless (Mesa)");
    }
    const bool shouldWarn = gpu.present() && isSoftwareRenderer(thread.contextDescription());
    EXPECT_EQ(!thread.softwareRendererWarning().empty(), shouldWarn)
        << "renderer " << thread.contextDescription() << ", warning: '" << thread.softwareRendererWarning() << "'";
}

TEST(SoftwareRenderer, OsMesaNeverWarns) {
    // Asked for by name: the user chose a software renderer.
    GlRenderThread thread(GlBackend::OsMesa);
    EXPECT_EQ(thread.contextOrigin(), "OSMesa");
    EXPECT_EQ(thread.softwareRendererWarning(), "");
}
