// The reference's distant lights (DomeLightSampling.h): they carry the
// dome's light, they sit where the light is, they turn with the dome, and
// they are the same every run.

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "hdHair/environment/DomeLightSampling.h"
#include "hdHair/environment/LatlongDirections.h"

namespace hdhair {
namespace {

constexpr double kPi = 3.14159265358979323846;

double luminance(const glm::vec3& rgb) { return 0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b; }

// Σ_k E_k max(0, n·ω_k): the lights' estimate of the irradiance onto a
// plane of normal n, which for a uniform dome of radiance L is π L.
glm::dvec3 planeIrradiance(const std::vector<SampledDomeLight>& lights, const glm::vec3& normal) {
    glm::dvec3 sum(0.0);
    for (const SampledDomeLight& light : lights)
        sum += glm::dvec3(light.irradiance) * double(std::max(0.0f, glm::dot(normal, light.direction)));
    return sum;
}

TEST(DomeLightSampling, AUniformDomeLightsEveryPlaneWithPiTimesItsRadiance) {
    const glm::vec3 radiance(0.5f, 1.0f, 2.0f);
    const std::vector<SampledDomeLight> lights = sampleDomeLights(uniformDomeGrid(radiance, 128, 64), glm::dmat4(1.0), 1024);
    ASSERT_EQ(lights.size(), 1024u);
    // Every light carries the same share of the dome's 4π L.
    for (const SampledDomeLight& light : lights) {
        EXPECT_NEAR(light.irradiance.r, 4.0 * kPi * 0.5 / 1024.0, 1e-6);
        EXPECT_NEAR(light.irradiance.b, 4.0 * kPi * 2.0 / 1024.0, 1e-6);
        EXPECT_NEAR(glm::length(light.direction), 1.0f, 1e-5f);
    }
    // Stratified: within 1 % of π L on planes facing anywhere.
    for (const glm::vec3 normal : {glm::vec3(0, 1, 0), glm::vec3(0, -1, 0), glm::vec3(1, 0, 0),
                                   glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f))}) {
        const glm::dvec3 irradiance = planeIrradiance(lights, normal);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(irradiance[c] / (kPi * radiance[c]), 1.0, 0.01) << c;
    }
}

TEST(DomeLightSampling, LightsGoWhereTheLightIsAndTurnWithTheDome) {
    // A dark dome with one bright cell-sized patch at +Z (the image's centre).
    RadianceGrid grid = uniformDomeGrid(glm::vec3(0.01f), 64, 32);
    size_t brightCells = 0;
    for (size_t c = 0; c < grid.cellCount(); ++c)
        if (glm::dot(grid.directions[c], glm::vec3(0, 0, 1)) > 0.99f) {
            grid.radiance[c] = glm::vec3(100.0f);
            ++brightCells;
        }
    ASSERT_GT(brightCells, 0u);
    const std::vector<SampledDomeLight> lights = sampleDomeLights(grid, glm::dmat4(1.0), 512);
    int towardsPatch = 0;
    for (const SampledDomeLight& light : lights) towardsPatch += glm::dot(light.direction, glm::vec3(0, 0, 1)) > 0.98f;
    // The patch holds most of the dome's light, so it gets most of the lights.
    EXPECT_GT(towardsPatch, 256);
    // Turned 90° about +Y, the dome lights from +X what it lit from +Z
    // (LatlongDirections.h); the lights turn with it, one for one.
    const glm::dmat4 turned = glm::rotate(glm::dmat4(1.0), kPi / 2.0, glm::dvec3(0, 1, 0));
    const std::vector<SampledDomeLight> turnedLights = sampleDomeLights(grid, turned, 512);
    ASSERT_EQ(turnedLights.size(), lights.size());
    for (size_t k = 0; k < lights.size(); ++k) {
        const glm::vec3 expected = glm::vec3(glm::dmat3(turned) * glm::dvec3(lights[k].direction));
        EXPECT_NEAR(glm::dot(turnedLights[k].direction, expected), 1.0f, 1e-5f) << k;
        EXPECT_EQ(turnedLights[k].irradiance, lights[k].irradiance);
    }
    int towardsX = 0;
    for (const SampledDomeLight& light : turnedLights) towardsX += glm::dot(light.direction, glm::vec3(1, 0, 0)) > 0.98f;
    EXPECT_NEAR(towardsX, towardsPatch, 2);  // the same lights, up to rounding at the 0.98 edge
}

TEST(DomeLightSampling, TheLightsCarryTheDomesLuminousPowerExactly) {
    RadianceGrid grid = uniformDomeGrid(glm::vec3(0.0f), 32, 16);
    double power = 0.0;
    for (size_t c = 0; c < grid.cellCount(); ++c) {
        grid.radiance[c] = glm::vec3(float(c % 7), float(c % 5) * 0.5f, float(c % 3));
        power += luminance(grid.radiance[c]) * grid.solidAngles[c];
    }
    const std::vector<SampledDomeLight> lights = sampleDomeLights(grid, glm::dmat4(1.0), 1000);
    double sum = 0.0;
    for (const SampledDomeLight& light : lights) {
        EXPECT_TRUE(std::isfinite(light.irradiance.r) && std::isfinite(light.irradiance.g) &&
                    std::isfinite(light.irradiance.b));
        sum += luminance(light.irradiance);
    }
    EXPECT_NEAR(sum / power, 1.0, 1e-4);
}

TEST(DomeLightSampling, DeterministicEmptyAndBoundedRequests) {
    const RadianceGrid grid = uniformDomeGrid(glm::vec3(1.0f, 0.5f, 0.25f), 16, 8);
    const std::vector<SampledDomeLight> a = sampleDomeLights(grid, glm::dmat4(1.0), 300);
    const std::vector<SampledDomeLight> b = sampleDomeLights(grid, glm::dmat4(1.0), 300);
    ASSERT_EQ(a.size(), b.size());
    for (size_t k = 0; k < a.size(); ++k) {
        EXPECT_EQ(a[k].direction, b[k].direction);
        EXPECT_EQ(a[k].irradiance, b[k].irradiance);
    }
    EXPECT_TRUE(sampleDomeLights(uniformDomeGrid(glm::vec3(0.0f), 16, 8), glm::dmat4(1.0), 100).empty());
    EXPECT_THROW(sampleDomeLights(grid, glm::dmat4(1.0), 0), std::invalid_argument);
    EXPECT_THROW(sampleDomeLights(grid, glm::dmat4(1.0), kMaxSampledDomeLights + 1), std::invalid_argument);
}

}  // namespace
}  // namespace hdhair
