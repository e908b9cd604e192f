#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include <glad/gl.h>
#include <gtest/gtest.h>

#include "hdHair/gl/GlRenderThread.h"

using namespace hdhair::gl;

class GlBackends : public ::testing::TestWithParam<GlBackend> {};

TEST_P(GlBackends, MakesAnOpenGL45CoreContextOnItsOwnThread) {
    GlRenderThread thread(GetParam());
    EXPECT_NE(thread.contextDescription().find("4.5"), std::string::npos) << thread.contextDescription();
    GLint major = 0, minor = 0, profile = 0;
    thread.run([&] {
        glGetIntegerv(GL_MAJOR_VERSION, &major);
        glGetIntegerv(GL_MINOR_VERSION, &minor);
        glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    });
    EXPECT_GE(major * 10 + minor, 45);
    EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
}

TEST_P(GlBackends, JobResultsAndExceptionsReachTheCaller) {
    GlRenderThread thread(GetParam());
    EXPECT_EQ(thread.run([] { return 42; }), 42);
    EXPECT_THROW(thread.run([]() -> int { throw std::runtime_error("job failed"); }), std::runtime_error);
    EXPECT_EQ(thread.run([] { return 7; }), 7);  // the thread survives a failed job
}

INSTANTIATE_TEST_SUITE_P(Headless, GlBackends, ::testing::Values(GlBackend::Egl, GlBackend::OsMesa),
                         [](const ::testing::TestParamInfo<GlBackend>& backend) { return std::string(toString(backend.param)); });

TEST(GlBackendChoice, EnvironmentVariableSelectsTheBackend) {
    ::setenv("HDHAIR_GL", "osmesa", 1);
    EXPECT_EQ(defaultGlBackend(), GlBackend::OsMesa);
    ::setenv("HDHAIR_GL", "vulkan", 1);
    EXPECT_THROW(defaultGlBackend(), std::invalid_argument);
    ::unsetenv("HDHAIR_GL");
    EXPECT_EQ(defaultGlBackend(), GlBackend::Egl);
}

// libglvnd reads its vendor list once per process, so the broken-EGL case
// runs in a child process (a gtest death test) and leaves this one intact.
TEST(GlBackendChoiceDeathTest, NoUsableEglContextSaysWhatWasTried) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    auto tryEglWithoutDriver = [] {
        ::setenv("__EGL_VENDOR_LIBRARY_FILENAMES", "/nonexistent/egl_vendor.json", 1);
        try {
            GlRenderThread thread(GlBackend::Egl);
        } catch (const GlUnavailableError& error) {
            std::fprintf(stderr, "%s\n", error.what());
            std::exit(3);
        }
        std::exit(0);
    };
    EXPECT_EXIT(tryEglWithoutDriver(), ::testing::ExitedWithCode(3),
                "no usable OpenGL 4.5 context through EGL \\(tried: .*\\); try --gl osmesa");
}
