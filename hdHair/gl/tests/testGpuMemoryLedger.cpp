// The GPU memory ledger (hdHair/gl/GpuMemory.h): buffers and textures are
// counted under their use while they live, scopes name what code does not,
// and each GL thread keeps its own count.

#include <stdexcept>

#include <gtest/gtest.h>

#include "hdHair/gl/GlObjects.h"
#include "hdHair/gl/GlRenderThread.h"
#include "hdHair/gl/GpuMemory.h"

using namespace hdhair::gl;

TEST(GpuMemoryLedger, TexelSizesOfTheFormatsInUse) {
    EXPECT_EQ(texelBytes(GL_RGBA32F), 16u);
    EXPECT_EQ(texelBytes(GL_RGB32F), 12u);
    EXPECT_EQ(texelBytes(GL_RGBA16F), 8u);
    EXPECT_EQ(texelBytes(GL_R32F), 4u);
    EXPECT_EQ(texelBytes(GL_R32I), 4u);
    EXPECT_EQ(texelBytes(GL_DEPTH_COMPONENT32F), 4u);
    EXPECT_THROW(texelBytes(GL_RGB565), std::logic_error);  // unknown: fails loudly, never counts 0
}

TEST(GpuMemoryLedger, CountsLiveObjectsByUseAndForgetsDeletedOnes) {
    GlRenderThread thread(GlBackend::Egl);
    thread.run([] {
        const auto before = gpuBytesByUse();
        {
            Buffer named = createBuffer(nullptr, 1000, GL_DYNAMIC_STORAGE_BIT, "strandGeometry");
            Buffer scoped, unnamed;
            {
                const GpuMemoryUse outer("drawOrder");
                scoped = createBuffer(nullptr, 300);
                {
                    const GpuMemoryUse inner("frameTarget");
                    GLuint name = 0;
                    glCreateTextures(GL_TEXTURE_2D_MULTISAMPLE, 1, &name);
                    Texture texture(name);
                    glTextureStorage2DMultisample(name, 4, GL_RGBA32F, 8, 4, GL_TRUE);
                    recordTextureStorage(name, GL_RGBA32F, 8, 4, 1, 4);
                    EXPECT_EQ(gpuBytesByUse()["frameTarget"], 8u * 4u * 4u * 16u);
                }  // the texture is deleted here
                const Buffer stillOuter = createBuffer(nullptr, 20);
                EXPECT_EQ(gpuBytesByUse()["drawOrder"], 320u);
            }
            unnamed = createBuffer(nullptr, 7);
            auto now = gpuBytesByUse();
            EXPECT_EQ(now["strandGeometry"], before.count("strandGeometry") ? before.at("strandGeometry") + 1000 : 1000);
            EXPECT_EQ(now["drawOrder"], 300u);
            EXPECT_EQ(now.count("frameTarget") ? now["frameTarget"] : 0u, 0u);
            EXPECT_EQ(now["other"], (before.count("other") ? before.at("other") : 0u) + 7u);
        }
        EXPECT_EQ(gpuBytesByUse(), before);  // everything made here is gone
    });
}

TEST(GpuMemoryLedger, EachGlThreadCountsItsOwnContext) {
    GlRenderThread first(GlBackend::Egl), second(GlBackend::Egl);
    Buffer* kept = nullptr;
    first.run([&] { kept = new Buffer(createBuffer(nullptr, 4096, 0, "meshGeometry")); });
    EXPECT_EQ(first.run([] { return gpuBytesByUse()["meshGeometry"]; }), 4096u);
    EXPECT_EQ(second.run([] { return gpuBytesByUse().count("meshGeometry"); }), 0u);
    first.run([&] { delete kept; });
    EXPECT_EQ(first.run([] { return gpuBytesByUse().count("meshGeometry"); }), 0u);
}
