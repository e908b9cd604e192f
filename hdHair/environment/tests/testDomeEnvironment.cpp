#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

#include "hdHair/environment/DomeEnvironment.h"
#include "hdHair/environment/LatlongDirections.h"
#include "hdHair/environment/tests/LatlongTestTextures.h"

using namespace hdhair;
using hdhair::test::TemporaryFolder;

namespace {

LightPrim dome(const std::string& textureFile, const std::string& format = "automatic") {
    LightPrim light;
    light.path = "/World/sky";
    light.type = LightType::Dome;
    light.textureFile = textureFile;
    light.textureFormat = format;
    return light;
}

// Every warning as "where: message", one a line.
std::string allWarnings(const Diagnostics& diagnostics) {
    std::string text;
    for (const Diagnostic& d : diagnostics.warnings()) text += d.where + ": " + d.message + "\n";
    return text;
}

bool mentions(const Diagnostics& diagnostics, std::initializer_list<std::string> fragments) {
    for (const Diagnostic& d : diagnostics.warnings()) {
        bool all = true;
        for (const std::string& fragment : fragments) all = all && (d.where + ": " + d.message).find(fragment) != std::string::npos;
        if (all) return true;
    }
    return false;
}

// A 256 × 128 EXR: a dim grey dome with one bright disc, 5° across (as
// small as a lobe shows: the fit's prefilter makes it a λ = 64 lobe),
// around `bright`, in the dome's frame.
std::string writeBrightSpotMap(const TemporaryFolder& folder, const glm::vec3& bright) {
    const std::string path = folder.path("spot.exr");
    test::writeTestImage(path, 256, 128, 3, test::latlongPixels(256, 128, [&](const glm::vec3& d) {
        return glm::dot(d, bright) > std::cos(glm::radians(2.5f)) ? glm::vec3(200.0f) : glm::vec3(0.1f);
    }));
    return path;
}

float degreesBetween(const glm::vec3& a, const glm::vec3& b) {
    return glm::degrees(std::acos(glm::clamp(glm::dot(a, b), -1.0f, 1.0f)));
}

}  // namespace

TEST(DomeEnvironment, AnUntexturedDomeIsUniformAndFitsNothing) {
    DomeTextureFitCache cache;
    Diagnostics diagnostics;
    const DomeEnvironment environment = domeEnvironment(dome(""), glm::vec3(0.5f, 1.0f, 2.0f), {}, diagnostics, cache);
    EXPECT_EQ(environment.lightPath, "/World/sky");
    EXPECT_EQ(environment.uniformRadiance, glm::vec3(0.5f, 1.0f, 2.0f));
    EXPECT_TRUE(environment.srbfs.empty());
    EXPECT_EQ(environmentRadiance(environment, glm::vec3(0, -1, 0)), glm::vec3(0.5f, 1.0f, 2.0f));
    EXPECT_EQ(diagnostics.warningCount(), 0u);
    EXPECT_EQ(cache.fitsComputed(), 0u);
}

TEST(DomeEnvironment, AMissingOrUnusableTextureWarnsAndLeavesTheDomeUniform) {
    TemporaryFolder folder;
    DomeTextureFitCache cache;
    const glm::vec3 scale(3.0f);
    const std::string missing = folder.path("missing.exr");
    Diagnostics diagnostics;
    const DomeEnvironment environment = domeEnvironment(dome(missing), scale, {}, diagnostics, cache);
    EXPECT_EQ(environment.uniformRadiance, scale);
    EXPECT_TRUE(environment.srbfs.empty());
    ASSERT_EQ(diagnostics.warningCount(), 1u);
    EXPECT_TRUE(mentions(diagnostics, {"/World/sky.inputs:texture:file", "'" + missing + "'", "uniformly"}))
        << allWarnings(diagnostics);

    const std::string huge = folder.path("huge.hdr");
    std::ofstream(huge, std::ios::binary) << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 100000 +X 200000\n";
    Diagnostics hugeDiagnostics;
    EXPECT_EQ(domeEnvironment(dome(huge), scale, {}, hugeDiagnostics, cache).uniformRadiance, scale);
    EXPECT_TRUE(mentions(hugeDiagnostics, {"/World/sky", huge, "200000 × 100000"})) << allWarnings(hugeDiagnostics);

    const std::string spot = writeBrightSpotMap(folder, glm::vec3(0, 0, 1));
    for (const char* format : {"mirroredBall", "angular", "cubeMapVerticalCross", "sideways"}) {
        Diagnostics formatDiagnostics;
        const DomeEnvironment unsupported = domeEnvironment(dome(spot, format), scale, {}, formatDiagnostics, cache);
        EXPECT_TRUE(unsupported.srbfs.empty());
        EXPECT_EQ(unsupported.uniformRadiance, scale);
        EXPECT_TRUE(mentions(formatDiagnostics, {"/World/sky.inputs:texture:format", std::string("'") + format + "'", spot}))
            << allWarnings(formatDiagnostics);
    }
}

TEST(DomeEnvironment, RepairedTexelsAreCountedInAWarning) {
    TemporaryFolder folder;
    std::vector<float> pixels(16 * 8 * 3, 1.0f);
    pixels[0] = std::nanf("");
    pixels[30] = -1.0f;
    const std::string path = folder.path("nan.exr");
    test::writeTestImage(path, 16, 8, 3, pixels);
    DomeTextureFitCache cache;
    Diagnostics diagnostics;
    const DomeEnvironment environment = domeEnvironment(dome(path), glm::vec3(1.0f), {}, diagnostics, cache);
    EXPECT_FALSE(environment.srbfs.empty());
    EXPECT_TRUE(mentions(diagnostics, {"/World/sky.inputs:texture:file", "2 texel(s)", path})) << allWarnings(diagnostics);
}

// One bright region: the strongest lobe points at it, in the dome's frame;
// turning the dome 90° about +Y (which takes +Z to +X) turns that lobe from
// +Z to +X, where Storm shows the same texel (LatlongDirections.h).
TEST(DomeEnvironment, TurningTheDomeTurnsItsLobes) {
    TemporaryFolder folder;
    const std::string path = writeBrightSpotMap(folder, glm::vec3(0, 0, 1));
    DomeTextureFitCache cache;
    Diagnostics diagnostics;
    LightPrim light = dome(path, "latlong");
    const DomeEnvironment still = domeEnvironment(light, glm::vec3(1.0f), {}, diagnostics, cache);
    ASSERT_FALSE(still.srbfs.empty());
    EXPECT_LT(degreesBetween(still.srbfs[0].lobe.centre, glm::vec3(0, 0, 1)), 2.0f);
    EXPECT_EQ(still.uniformRadiance, glm::vec3(0.0f));

    light.worldTransform = glm::rotate(glm::dmat4(1.0), glm::radians(90.0), glm::dvec3(0, 1, 0));
    const DomeEnvironment turned = domeEnvironment(light, glm::vec3(1.0f), {}, diagnostics, cache);
    ASSERT_EQ(turned.srbfs.size(), still.srbfs.size());
    EXPECT_LT(degreesBetween(turned.srbfs[0].lobe.centre, glm::vec3(1, 0, 0)), 2.0f);
    for (size_t i = 0; i < still.srbfs.size(); ++i) {
        const glm::vec3 expected(still.srbfs[i].lobe.centre.z, still.srbfs[i].lobe.centre.y, -still.srbfs[i].lobe.centre.x);
        EXPECT_LT(glm::length(turned.srbfs[i].lobe.centre - expected), 1e-5f) << i;
        EXPECT_EQ(turned.srbfs[i].amplitude, still.srbfs[i].amplitude);
    }
    EXPECT_GT(environmentRadiance(turned, glm::vec3(1, 0, 0)).r, 10.0f * environmentRadiance(turned, glm::vec3(0, 0, 1)).r);
    EXPECT_EQ(cache.fitsComputed(), 1u) << "turning a dome needs no new fit";
    EXPECT_EQ(diagnostics.warningCount(), 0u) << allWarnings(diagnostics);
}

// inputs:color (with intensity and exposure, in radianceScale) tints the
// texture channel by channel.
TEST(DomeEnvironment, TheRadianceScaleTintsTheTexture) {
    TemporaryFolder folder;
    const std::string path = writeBrightSpotMap(folder, glm::vec3(0, 1, 0));
    DomeTextureFitCache cache;
    Diagnostics diagnostics;
    const DomeEnvironment white = domeEnvironment(dome(path), glm::vec3(1.0f), {}, diagnostics, cache);
    const DomeEnvironment tinted = domeEnvironment(dome(path), glm::vec3(4.0f, 1.0f, 0.5f), {}, diagnostics, cache);
    ASSERT_EQ(white.srbfs.size(), tinted.srbfs.size());
    for (size_t i = 0; i < white.srbfs.size(); ++i)
        EXPECT_EQ(tinted.srbfs[i].amplitude, white.srbfs[i].amplitude * glm::vec3(4.0f, 1.0f, 0.5f));
    EXPECT_EQ(tinted.fitError, white.fitError);
}

// Fits are kept per file and settings, computed once however many threads
// ask, and again when the file changes.
TEST(DomeTextureFitCache, OneFitPerFileAndSettings) {
    TemporaryFolder folder;
    const std::string path = writeBrightSpotMap(folder, glm::vec3(1, 0, 0));
    DomeTextureFitCache cache;
    std::vector<std::shared_ptr<const DomeTextureFit>> fits(4);
    std::vector<std::thread> threads;
    for (size_t i = 0; i < fits.size(); ++i)
        threads.emplace_back([&, i] { fits[i] = cache.latlongFit(path, DomeFitSettings()); });
    for (std::thread& thread : threads) thread.join();
    EXPECT_EQ(cache.fitsComputed(), 1u);
    for (const auto& fit : fits) EXPECT_EQ(fit.get(), fits[0].get());
    EXPECT_TRUE(fits[0]->error.empty()) << fits[0]->error;
    EXPECT_EQ(fits[0]->imageWidth, 256);

    DomeFitSettings fewer;
    fewer.srbf.maxLobes = 10;
    EXPECT_LE(cache.latlongFit(path, fewer)->fit.srbfs.size(), 10u);
    EXPECT_EQ(cache.fitsComputed(), 2u);

    // The same file written again (its time moves on): fitted again.
    std::filesystem::last_write_time(path, std::filesystem::last_write_time(path) + std::chrono::seconds(2));
    cache.latlongFit(path, DomeFitSettings());
    EXPECT_EQ(cache.fitsComputed(), 3u);
    EXPECT_EQ(cache.size(), 3u);
    cache.clear();
    EXPECT_EQ(cache.size(), 0u);
}

// A 1024 × 512 map, the interactive case, fits through the whole
// path (the time is hdhair-bench's business: SrbfFit/1024x512).
TEST(DomeEnvironment, AOneKSkyFits) {
    TemporaryFolder folder;
    const glm::vec3 sun = glm::normalize(glm::vec3(-0.3f, 0.5f, 0.8f));
    const std::string path = folder.path("sky.exr");
    test::writeTestImage(path, 1024, 512, 3, test::latlongPixels(1024, 512, [&](const glm::vec3& d) {
        return test::proceduralSky(d, sun);
    }), OIIO::TypeDesc::HALF);
    DomeTextureFitCache cache;
    Diagnostics diagnostics;
    const DomeEnvironment environment = domeEnvironment(dome(path), glm::vec3(1.0f), {}, diagnostics, cache);
    EXPECT_EQ(environment.srbfs.size(), 30u);
    EXPECT_LT(degreesBetween(environment.srbfs[0].lobe.centre, sun), 3.0f);
    EXPECT_LT(environment.fitError, 0.2f);
    EXPECT_EQ(diagnostics.warningCount(), 0u) << allWarnings(diagnostics);
}

TEST(DomeEnvironment, TheReferenceSamplesTheTextureTurnedScaledAndUnblurred) {
    TemporaryFolder folder;
    const glm::vec3 bright = glm::normalize(glm::vec3(0.0f, 0.2f, 1.0f));
    LightPrim sky = dome(writeBrightSpotMap(folder, bright));
    sky.worldTransform = glm::rotate(glm::dmat4(1.0), glm::radians(90.0), glm::dvec3(0.0, 1.0, 0.0));
    Diagnostics diagnostics;
    const glm::vec3 scale(2.0f, 1.0f, 0.5f);
    const DomeEnvironment sampled = sampledDomeEnvironment(sky, scale, 256, diagnostics);
    EXPECT_EQ(diagnostics.warningCount(), 0u) << allWarnings(diagnostics);
    EXPECT_TRUE(sampled.srbfs.empty());
    EXPECT_EQ(sampled.uniformRadiance, glm::vec3(0.0f));
    ASSERT_EQ(sampled.sampledLights.size(), 256u);
    // The disc (1.2 of luminous power, against the grey dome's 1.26) draws
    // about half the samples, all within 4° (its 2.5° radius and a 1.4° cell)
    // of the turned direction (+Z turned 90° about +Y is +X): the map as it
    // is, not its λ = 64 (7°) prefiltered fit.
    const glm::vec3 turned = domeLightDirectionToWorld(sky.worldTransform, bright);
    size_t inDisc = 0;
    glm::vec3 total(0.0f);
    for (const SampledDomeLight& light : sampled.sampledLights) {
        inDisc += degreesBetween(light.direction, turned) < 4.0f ? 1 : 0;
        total += light.irradiance;
    }
    EXPECT_GT(inDisc, 100u);
    EXPECT_LT(inDisc, 156u);
    // Tinted per channel by the radiance scale.
    EXPECT_NEAR(total.r / total.g, 2.0f, 1e-3f);
    EXPECT_NEAR(total.b / total.g, 0.5f, 1e-3f);
}

TEST(DomeEnvironment, TheReferenceSamplesAnUntexturedOrUnusableDomeUniformly) {
    TemporaryFolder folder;
    Diagnostics diagnostics;
    const DomeEnvironment uniform = sampledDomeEnvironment(dome(""), glm::vec3(1.0f), 64, diagnostics);
    EXPECT_EQ(diagnostics.warningCount(), 0u);
    const std::string missing = folder.path("none.exr");
    const DomeEnvironment fallback = sampledDomeEnvironment(dome(missing), glm::vec3(1.0f), 64, diagnostics);
    EXPECT_TRUE(mentions(diagnostics, {"/World/sky.inputs:texture:file", missing, "lit uniformly"}))
        << allWarnings(diagnostics);
    ASSERT_EQ(uniform.sampledLights.size(), 64u);
    ASSERT_EQ(fallback.sampledLights.size(), 64u);
    // Uniform radiance 1 is π of irradiance on any plane; over the sphere,
    // the lights' irradiance sums to 4π.
    glm::vec3 total(0.0f);
    for (size_t k = 0; k < 64; ++k) {
        EXPECT_EQ(uniform.sampledLights[k].direction, fallback.sampledLights[k].direction);
        total += uniform.sampledLights[k].irradiance;
    }
    EXPECT_NEAR(total.g, 4.0f * 3.14159265f, 1e-3f);
}
