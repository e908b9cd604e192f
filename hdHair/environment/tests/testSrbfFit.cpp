#include <gtest/gtest.h>

#include <iostream>

#include <cmath>
#include <cstring>
#include <numeric>

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/trigonometric.hpp>

#include "hdHair/environment/LatlongDirections.h"
#include "hdHair/environment/SrbfFit.h"
#include "hdHair/environment/tests/LatlongTestTextures.h"

using namespace hdhair;

namespace {

// A grid whose every cell's radiance is radiance(cell centre).
RadianceGrid sampledGrid(int width, int height, const std::function<glm::vec3(const glm::vec3&)>& radiance) {
    RadianceGrid grid = latlongGrid(width, height);
    for (size_t s = 0; s < grid.cellCount(); ++s) grid.radiance[s] = radiance(grid.directions[s]);
    return grid;
}

// n directions spread evenly over the sphere (a Fibonacci lattice): for
// checking a fit away from the grid it was fitted on.
std::vector<glm::vec3> sphereDirections(int n) {
    std::vector<glm::vec3> directions;
    const float golden = glm::pi<float>() * (3.0f - std::sqrt(5.0f));
    for (int i = 0; i < n; ++i) {
        const float y = 1.0f - 2.0f * (float(i) + 0.5f) / float(n);
        const float r = std::sqrt(1.0f - y * y);
        directions.emplace_back(r * std::cos(golden * float(i)), y, r * std::sin(golden * float(i)));
    }
    return directions;
}

float degreesBetween(const glm::vec3& a, const glm::vec3& b) {
    return glm::degrees(std::acos(glm::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0f, 1.0f)));
}

const glm::vec3 kSun = glm::normalize(glm::vec3(0.5f, 0.6f, 0.3f));

}  // namespace

TEST(Srbf, TheKernelAsThePaperWritesIt) {
    const glm::vec3 up(0, 1, 0);
    EXPECT_EQ(srbfKernel(up, up, 16.0f), 1.0f);
    EXPECT_NEAR(srbfKernel(glm::vec3(1, 0, 0), up, 16.0f), std::exp(-16.0f), 1e-12f);
    EXPECT_NEAR(srbfKernel(-up, up, 16.0f), std::exp(-32.0f), 1e-18f);
    // ∫ G dω, as the digest (§2.1) works it out, and against a fine grid.
    EXPECT_NEAR(srbfIntegral(16.0f), 0.3927f, 1e-4f);
    EXPECT_NEAR(srbfIntegral(64.0f), 0.0982f, 1e-4f);
    const RadianceGrid fine = latlongGrid(1024, 512);
    double integral = 0.0;
    for (size_t s = 0; s < fine.cellCount(); ++s) integral += fine.solidAngles[s] * srbfKernel(fine.directions[s], up, 40.0f);
    EXPECT_NEAR(integral, srbfIntegral(40.0f), 2e-4 * integral);
    // The 10⁻³ cut-off (digest table, §2.2).
    EXPECT_NEAR(srbfSupportCosine(16.0f), 0.5683f, 1e-4f);
    EXPECT_NEAR(srbfSupportCosine(64.0f), 0.8921f, 1e-4f);
}

// A map that is one SRBF is fitted by that SRBF.
TEST(SrbfFit, OneLobeIsFoundAgain) {
    const RadianceGrid probe = latlongGrid(64, 32);
    const glm::vec3 centre = probe.directions[10 * 64 + 20];  // a cell centre
    const RadianceGrid grid = sampledGrid(64, 32, [&](const glm::vec3& d) {
        return glm::vec3(2.0f, 1.0f, 0.5f) * srbfKernel(d, centre, 32.0f);
    });
    SrbfFitSettings settings;
    settings.maxLobes = 1;
    settings.prefilterBandwidth = 0.0f;  // the map is an SRBF already
    const SrbfFit fit = fitSrbfs(grid, settings);
    ASSERT_EQ(fit.srbfs.size(), 1u);
    EXPECT_LT(degreesBetween(fit.srbfs[0].lobe.centre, centre), 0.5f);
    EXPECT_NEAR(fit.srbfs[0].lobe.bandwidth, 32.0f, 1e-3f);  // one of the nine: 16 · 4^(4/8)
    EXPECT_NEAR(fit.srbfs[0].amplitude.r, 2.0f, 0.02f);
    EXPECT_NEAR(fit.srbfs[0].amplitude.b, 0.5f, 0.005f);
    EXPECT_LT(fit.relativeError, 0.01f);
    EXPECT_FLOAT_EQ(srbfRelativeError(grid, fit.srbfs), fit.relativeError);
}

// One bright cell, a sun smaller than any lobe: prefiltered with the
// narrowest lobe (the default) it becomes one λ = 64 lobe of its power.
// Fitted as it is, least squares alone would give that lobe twice the power
// (∫G / ∫G² = 2 for a point); the power equation (SrbfFit.h, step 1) keeps
// it either way.
TEST(SrbfFit, ThePrefilterKeepsASunsPower) {
    RadianceGrid grid = latlongGrid(64, 32);
    const size_t sunCell = 12 * 64 + 40;
    grid.radiance[sunCell] = glm::vec3(100.0f);
    const float power = 100.0f * grid.solidAngles[sunCell];
    SrbfFitSettings settings;
    settings.maxLobes = 1;
    const SrbfFit prefiltered = fitSrbfs(grid, settings);
    ASSERT_EQ(prefiltered.srbfs.size(), 1u);
    const Srbf& lobe = prefiltered.srbfs[0];
    EXPECT_NEAR(lobe.amplitude.r * srbfIntegral(lobe.lobe.bandwidth), power, 0.05f * power);
    EXPECT_LT(degreesBetween(lobe.lobe.centre, grid.directions[sunCell]), 1.0f);
    settings.prefilterBandwidth = 0.0f;
    const SrbfFit rawFit = fitSrbfs(grid, settings);
    ASSERT_EQ(rawFit.srbfs.size(), 1u);
    const Srbf& raw = rawFit.srbfs[0];
    EXPECT_NEAR(raw.amplitude.r * srbfIntegral(raw.lobe.bandwidth), power, 0.05f * power);
}

// The lobes emit the map's power, channel by channel, at every lobe count:
// what a wide sky's diffuse light on hair depends on most.
TEST(SrbfFit, TheFitKeepsTheMapsPower) {
    const glm::vec3 uniform(0.5f, 1.0f, 2.0f);
    const RadianceGrid flat = sampledGrid(64, 32, [&](const glm::vec3&) { return uniform; });
    const RadianceGrid sky = sampledGrid(64, 32, [](const glm::vec3& d) { return test::proceduralSky(d, kSun); });
    for (const RadianceGrid* grid : {&flat, &sky}) {
        glm::dvec3 mapPower(0.0);
        for (size_t s = 0; s < grid->cellCount(); ++s)
            mapPower += double(grid->solidAngles[s]) * glm::dvec3(grid->radiance[s]);
        for (int lobes : {10, 30, 60}) {
            SrbfFitSettings settings;
            settings.maxLobes = lobes;
            const SrbfFit fit = fitSrbfs(*grid, settings);
            glm::dvec3 fitPower(0.0);
            for (const Srbf& lobe : fit.srbfs)
                fitPower += double(srbfIntegral(lobe.lobe.bandwidth)) * glm::dvec3(lobe.amplitude);
            std::cout << (grid == &flat ? "uniform" : "sky") << ", " << lobes << " lobes: E " << fit.relativeError
                      << ", power " << fitPower.g / mapPower.g << " of the map's\n";
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(fitPower[c] / mapPower[c], 1.0, 0.01) << lobes << " lobes";
        }
    }
}

// A uniform map, fitted with 10, 30 and 60 lobes: its stated error holds
// away from the grid too (20,000 directions), and more lobes fit better.
TEST(SrbfFit, UniformMapsAreReproducedWithinTheStatedError) {
    const glm::vec3 uniform(0.5f, 1.0f, 2.0f);
    const RadianceGrid grid = sampledGrid(64, 32, [&](const glm::vec3&) { return uniform; });
    const std::vector<glm::vec3> directions = sphereDirections(20000);
    float previous = 1.0f;
    for (int lobes : {10, 30, 60}) {
        SrbfFitSettings settings;
        settings.maxLobes = lobes;
        const SrbfFit fit = fitSrbfs(grid, settings);
        EXPECT_LE(int(fit.srbfs.size()), lobes);
        EXPECT_LT(fit.relativeError, previous) << lobes << " lobes";
        previous = fit.relativeError;
        double error = 0.0, energy = 0.0;
        for (const glm::vec3& d : directions) {
            const glm::vec3 difference = srbfRadiance(fit.srbfs, d) - uniform;
            error += glm::dot(difference, difference);
            energy += glm::dot(uniform, uniform);
        }
        const float sphereError = float(std::sqrt(error / energy));
        EXPECT_LT(sphereError, 1.1f * fit.relativeError + 0.005f) << lobes << " lobes";
        for (const Srbf& lobe : fit.srbfs) {
            EXPECT_GE(lobe.lobe.bandwidth, kMinSrbfBandwidth);
            EXPECT_LE(lobe.lobe.bandwidth, kMaxSrbfBandwidth);
            EXPECT_GE(std::min({lobe.amplitude.r, lobe.amplitude.g, lobe.amplitude.b}), 0.0f);
        }
    }
    EXPECT_LT(previous, 0.06f) << "60 lobes";
}

TEST(SrbfFit, TheStrongestLobeIsTheSun) {
    const RadianceGrid grid = sampledGrid(64, 32, [](const glm::vec3& d) { return test::proceduralSky(d, kSun); });
    const SrbfFit fit = fitSrbfs(grid);
    ASSERT_FALSE(fit.srbfs.empty());
    EXPECT_LT(degreesBetween(fit.srbfs[0].lobe.centre, kSun), 3.0f);
    EXPECT_LT(fit.relativeError, 0.2f);
}

TEST(SrbfFit, FitsAreDeterministic) {
    const RadianceGrid grid = sampledGrid(64, 32, [](const glm::vec3& d) { return test::proceduralSky(d, kSun); });
    const SrbfFit first = fitSrbfs(grid);
    const SrbfFit second = fitSrbfs(grid);
    ASSERT_EQ(first.srbfs.size(), second.srbfs.size());
    EXPECT_EQ(std::memcmp(first.srbfs.data(), second.srbfs.data(), first.srbfs.size() * sizeof(Srbf)), 0);
    EXPECT_EQ(first.relativeError, second.relativeError);
}

TEST(SrbfFit, ATargetErrorStopsInsertionEarly) {
    const RadianceGrid grid = sampledGrid(64, 32, [](const glm::vec3& d) { return test::proceduralSky(d, kSun); });
    SrbfFitSettings settings;
    settings.maxLobes = 60;
    settings.targetError = 0.5f;
    const SrbfFit fit = fitSrbfs(grid, settings);
    EXPECT_LT(fit.srbfs.size(), 60u);
    EXPECT_LE(fit.relativeError, 0.5f);
}

TEST(SrbfFit, BlackMapsNeedNoLightsAndBadSettingsAreRefused) {
    const SrbfFit black = fitSrbfs(latlongGrid(16, 8));
    EXPECT_TRUE(black.srbfs.empty());
    EXPECT_EQ(black.relativeError, 0.0f);
    SrbfFitSettings none;
    none.maxLobes = 0;
    EXPECT_THROW(fitSrbfs(latlongGrid(16, 8), none), std::invalid_argument);
    SrbfFitSettings negative;
    negative.targetError = -1.0f;
    EXPECT_THROW(fitSrbfs(latlongGrid(16, 8), negative), std::invalid_argument);
}
