// The plugin's translation code that needs no OpenUSD: render-buffer writing,
// camera and light translation, refine levels.

#include <cstring>

#include <Imath/half.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <gtest/gtest.h>

#include "hdHair/hydra/CompositeOver.h"
#include "hdHair/hydra/HydraCamera.h"
#include "hdHair/hydra/HydraLights.h"
#include "hdHair/hydra/RenderBufferWriting.h"

using namespace hdhair;
using namespace hdhair::hydra;

TEST(RenderBufferWriting, ColorGoesBottomUpIntoTheDataWindowAsHalves) {
    // A 2x2 image into a 4x3 buffer at data window (1, 0): y-down in, bottom-up rows out.
    Image image(2, 2, 4);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x) image.at(x, y, 0) = float(10 * y + x) + 0.5f;
    std::vector<uint8_t> buffer(4 * 3 * 8, 0xff);
    ASSERT_TRUE(writeImageToBuffer(image, BufferFormat::Float16Vec4, {1, 0, 2, 2}, 4, 3, buffer.data()));
    auto red = [&](int x, int row) {
        Imath::half value;
        std::memcpy(&value, &buffer[(size_t(row) * 4 + size_t(x)) * 8], 2);
        return float(value);
    };
    // Image row 0 (top) is buffer row 2 (the top row counted from the bottom).
    EXPECT_EQ(red(1, 2), 0.5f);
    EXPECT_EQ(red(2, 2), 1.5f);
    EXPECT_EQ(red(1, 1), 10.5f);
    // Outside the data window the buffer is untouched.
    EXPECT_EQ(buffer[0], 0xff);
    EXPECT_EQ(buffer[(2 * 4 + 3) * 8], 0xff);
}

TEST(RenderBufferWriting, DepthIdsAndMismatchedSizes) {
    Image depth(1, 2, 1);
    depth.pixels = {0.25f, 0.75f};
    std::vector<uint8_t> buffer(2 * 4, 0);
    ASSERT_TRUE(writeImageToBuffer(depth, BufferFormat::Float32, {0, 0, 1, 2}, 1, 2, buffer.data()));
    float bottom;
    std::memcpy(&bottom, buffer.data(), 4);
    EXPECT_EQ(bottom, 0.75f);

    std::vector<uint8_t> ids(2 * 4, 0);
    ASSERT_TRUE(writeIdsToBuffer({7, -1}, {0, 0, 1, 2}, 1, 2, ids.data()));
    int32_t bottomId;
    std::memcpy(&bottomId, ids.data(), 4);
    EXPECT_EQ(bottomId, -1);

    EXPECT_FALSE(writeImageToBuffer(depth, BufferFormat::Float16Vec4, {0, 0, 1, 2}, 1, 2, buffer.data()));
    EXPECT_FALSE(writeImageToBuffer(depth, BufferFormat::Float32, {0, 0, 2, 2}, 1, 2, buffer.data()));
    EXPECT_FALSE(writeIdsToBuffer({1, 2, 3}, {0, 0, 1, 2}, 1, 2, ids.data()));
}

TEST(RenderBufferWriting, DataWindowsPartlyOutsideTheBufferAreClipped) {
    Image image(4, 4, 1, 1.0f);
    std::vector<uint8_t> buffer(3 * 3 * 4, 0);
    ASSERT_TRUE(writeImageToBuffer(image, BufferFormat::Float32, {-1, -1, 4, 4}, 3, 3, buffer.data()));
    DataWindow clipped = clipToBuffer({-1, -1, 4, 4}, 3, 3);
    EXPECT_EQ(clipped.x, 0);
    EXPECT_EQ(clipped.width, 3);
    EXPECT_EQ(clipToBuffer({5, 5, 2, 2}, 3, 3).width, 0);
}

TEST(RenderBufferWriting, UNorm8IsClampedAndRounded) {
    Image image(1, 1, 4);
    image.pixels = {-0.5f, 0.5f, 2.0f, NAN};
    std::vector<uint8_t> buffer(4, 0);
    ASSERT_TRUE(writeImageToBuffer(image, BufferFormat::UNorm8Vec4, {0, 0, 1, 1}, 1, 1, buffer.data()));
    EXPECT_EQ(buffer[0], 0);
    EXPECT_EQ(buffer[1], 128);
    EXPECT_EQ(buffer[2], 255);
    EXPECT_EQ(buffer[3], 0);
}

TEST(HydraCamera, GfMemoryIsTakenAsItIs) {
    // A GfMatrix4d translation by (1, 2, 3) stores it in its fourth row.
    double gf[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 2, 3, 1};
    glm::dvec4 moved = matrixFromGf(gf) * glm::dvec4(0, 0, 0, 1);
    EXPECT_EQ(moved, glm::dvec4(1, 2, 3, 1));
}

TEST(HydraCamera, ClippingPlanesAndProjectionKindAreRecovered) {
    glm::dmat4 view = glm::lookAt(glm::dvec3(0, 0, 10), glm::dvec3(0), glm::dvec3(0, 1, 0));
    glm::dmat4 perspective = glm::perspective(0.8, 1.5, 0.5, 200.0);
    CameraView camera = cameraViewFromHydra(glm::value_ptr(view), glm::value_ptr(perspective), 300, 200);
    EXPECT_FALSE(camera.orthographic);
    EXPECT_NEAR(camera.nearClip, 0.5, 1e-9);
    EXPECT_NEAR(camera.farClip, 200.0, 1e-6);
    glm::dmat4 ortho = glm::ortho(-2.0, 2.0, -1.0, 1.0, 1.0, 50.0);
    CameraView flat = cameraViewFromHydra(glm::value_ptr(view), glm::value_ptr(ortho), 300, 200);
    EXPECT_TRUE(flat.orthographic);
    EXPECT_NEAR(flat.nearClip, 1.0, 1e-9);
    EXPECT_NEAR(flat.farClip, 50.0, 1e-9);
    EXPECT_EQ(flat.imageWidth, 300);
}

TEST(HydraCamera, UnusableInputIsRejected) {
    double zero[16] = {};
    glm::dmat4 identity(1.0);
    EXPECT_THROW(cameraViewFromHydra(zero, glm::value_ptr(identity), 4, 4), std::invalid_argument);
    glm::dmat4 broken(1.0);
    broken[0][0] = NAN;
    EXPECT_THROW(cameraViewFromHydra(glm::value_ptr(identity), glm::value_ptr(broken), 4, 4), std::invalid_argument);
    EXPECT_THROW(cameraViewFromHydra(glm::value_ptr(identity), glm::value_ptr(identity), 0, 4), std::invalid_argument);
}

TEST(HydraCamera, RefineLevelsMapToComplexity) {
    EXPECT_EQ(complexityFromRefineLevel(0), Complexity::Low);
    EXPECT_EQ(complexityFromRefineLevel(1), Complexity::Medium);
    EXPECT_EQ(complexityFromRefineLevel(2), Complexity::High);
    EXPECT_EQ(complexityFromRefineLevel(3), Complexity::VeryHigh);
    EXPECT_EQ(complexityFromRefineLevel(8), Complexity::VeryHigh);
}

TEST(HydraLights, ParametersAndFallbacks) {
    LightParameterLookup lookup = [](const std::string& name) -> std::optional<std::vector<double>> {
        if (name == "intensity") return std::vector<double>{3.0};
        if (name == "color") return std::vector<double>{1.0, 0.5, 0.25};
        if (name == "radius") return std::vector<double>{2.0};
        if (name == "normalize") return std::vector<double>{1.0};
        if (name == "shadow:enable") return std::vector<double>{0.0};
        return std::nullopt;
    };
    LightPrim light = lightFromHydra("/L", LightType::Sphere, false, lookup, glm::dmat4(1.0));
    EXPECT_FALSE(light.shadowEnable);
    EXPECT_EQ(light.intensity, 3.0f);
    EXPECT_EQ(light.color, glm::vec3(1.0f, 0.5f, 0.25f));
    EXPECT_EQ(light.radius, 2.0f);
    EXPECT_TRUE(light.normalize);
    EXPECT_EQ(light.exposure, 0.0f);  // UsdLux fallback
    EXPECT_FALSE(light.hostCameraLight);
}

TEST(HydraLights, HostCameraLightHasUnitIntensity) {
    LightParameterLookup lookup = [](const std::string& name) -> std::optional<std::vector<double>> {
        if (name == "intensity") return std::vector<double>{15000.0};
        return std::nullopt;
    };
    LightPrim light = lightFromHydra("/host/light0", LightType::Distant, true, lookup, glm::dmat4(1.0));
    EXPECT_TRUE(light.hostCameraLight);
    EXPECT_TRUE(light.shadowEnable) << "ShadowAPI's fallback where the host gives nothing";
    EXPECT_EQ(light.intensity, 1.0f);
}

TEST(HydraLights, DomeTextureIsReadForDomesOnly) {
    LightParameterLookup lookup = [](const std::string&) -> std::optional<std::vector<double>> { return std::nullopt; };
    const HydraDomeTexture texture{"/maps/sky.exr", "latlong"};
    LightPrim dome = lightFromHydra("/dome", LightType::Dome, false, lookup, glm::dmat4(1.0), texture);
    EXPECT_EQ(dome.textureFile, "/maps/sky.exr");
    EXPECT_EQ(dome.textureFormat, "latlong");
    LightPrim unformatted = lightFromHydra("/dome", LightType::Dome, false, lookup, glm::dmat4(1.0), {"/a.hdr", ""});
    EXPECT_EQ(unformatted.textureFormat, "automatic");  // UsdLux's fallback when the host gives none
    LightPrim sphere = lightFromHydra("/sphere", LightType::Sphere, false, lookup, glm::dmat4(1.0), texture);
    EXPECT_EQ(sphere.textureFile, "");
}

TEST(CompositeOver, EmptyPixelsShowTheBackgroundAndCoveredOnesKeepTheirColour) {
    Image image(3, 1, 4);
    image.pixels = {0, 0, 0, 0, 0.5f, 0, 0, 0.5f, 1, 1, 1, 1};
    compositeOver(image, {0.2f, 0.4f, 0.6f, 1.0f});
    EXPECT_FLOAT_EQ(image.at(0, 0, 1), 0.4f);
    EXPECT_FLOAT_EQ(image.at(0, 0, 3), 1.0f);
    EXPECT_FLOAT_EQ(image.at(1, 0, 0), 0.6f);  // 0.5 + 0.5 * 0.2
    EXPECT_FLOAT_EQ(image.at(1, 0, 3), 1.0f);
    EXPECT_FLOAT_EQ(image.at(2, 0, 0), 1.0f);
}
