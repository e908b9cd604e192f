// Light views fitted to the casters (ShadowLightView.h): every corner of the
// bounds lands inside the map, depths are linear and cover the casters, and
// what one view cannot hold (a light inside the bounds, a transform that is
// not finite) is refused with a reason, never a wrong view.

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "hdHair/plan/ShadowLightView.h"

using namespace hdhair;

namespace {

CasterBounds box(glm::dvec3 min, glm::dvec3 max, double maxWidth = 0.0) {
    CasterBounds bounds;
    bounds.min = min;
    bounds.max = max;
    bounds.maxWidth = maxWidth;
    return bounds;
}

ShadingLight distant(glm::vec3 towardsLight) {
    ShadingLight light;
    light.directionOrPosition = glm::normalize(towardsLight);
    return light;
}

ShadingLight local(glm::vec3 position) {
    ShadingLight light;
    light.isLocal = true;
    light.directionOrPosition = position;
    return light;
}

// Every corner of `bounds` (grown by half the widest strand) inside the
// map's texels and depth range.
void expectHoldsEveryCorner(const ShadowLightView& view, const CasterBounds& bounds) {
    ASSERT_TRUE(view.valid) << view.fallback;
    const glm::dvec3 grow(0.5 * bounds.maxWidth);
    for (int i = 0; i < 8; ++i) {
        glm::dvec3 corner((i & 1) ? bounds.max.x + grow.x : bounds.min.x - grow.x,
                          (i & 2) ? bounds.max.y + grow.y : bounds.min.y - grow.y,
                          (i & 4) ? bounds.max.z + grow.z : bounds.min.z - grow.z);
        glm::dvec4 clip = view.projection * view.view * glm::dvec4(corner, 1.0);
        ASSERT_GT(clip.w, 0.0);
        glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
        EXPECT_LE(std::abs(ndc.x), 1.0) << i;
        EXPECT_LE(std::abs(ndc.y), 1.0) << i;
        EXPECT_LE(std::abs(ndc.z), 1.0) << i;
        const double depth = glm::dot(corner - view.eye, view.forward);
        EXPECT_GE(depth, view.nearDepth * (1.0 - 1e-9)) << i;
        EXPECT_LE(depth, view.farDepth * (1.0 + 1e-9)) << i;
    }
}

}  // namespace

TEST(ShadowLightView, DistantLightsAreOrthographicAndHoldTheBounds) {
    const CasterBounds bounds = box({-1.0, 0.0, -2.0}, {1.0, 3.0, 0.5}, 0.1);
    for (glm::vec3 direction : {glm::vec3(0, 1, 0), glm::vec3(1, 1, 1), glm::vec3(0.2f, -0.3f, 1.0f)}) {
        ShadowLightView view = fitShadowLightView(distant(direction), bounds, 256);
        expectHoldsEveryCorner(view, bounds);
        EXPECT_TRUE(view.orthographic);
        // It looks along the light: the forward direction is the light's travel.
        EXPECT_NEAR(glm::dot(view.forward, -glm::normalize(glm::dvec3(direction))), 1.0, 1e-9);
        // Square texels: one world size across the map.
        EXPECT_NEAR(view.texelSize, 2.0 / (view.projection[0][0] * 256.0), 1e-12);
        EXPECT_NEAR(view.projection[0][0], view.projection[1][1], 1e-12);
        EXPECT_EQ(view.resolution, 256);
        EXPECT_NEAR(view.pixelsPerUnit, view.projection[0][0] * 128.0, 1e-9);
    }
}

TEST(ShadowLightView, DistantWindowIsTheBoundsProjectionPlusAMargin) {
    // Looking down -Y at a 2 x 2 square (x, z): half-width 1, plus the
    // strands' half width 0.05, plus one texel each side.
    ShadowLightView view = fitShadowLightView(distant({0, 1, 0}), box({-1, 0, -1}, {1, 0, 1}, 0.1), 100);
    ASSERT_TRUE(view.valid);
    const double half = 1.0 / view.projection[0][0];
    EXPECT_NEAR(half, 1.05 * 100.0 / 98.0, 1e-9);
    // All hair at one depth still gets a depth range (a flat slab).
    EXPECT_GT(view.farDepth, view.nearDepth);
}

TEST(ShadowLightView, LocalLightsArePerspectiveFromTheLight) {
    const CasterBounds bounds = box({-1, -1, -1}, {1, 1, 1});
    ShadowLightView view = fitShadowLightView(local({0, 0, 10}), bounds, 512);
    expectHoldsEveryCorner(view, bounds);
    EXPECT_FALSE(view.orthographic);
    EXPECT_EQ(view.eye, glm::dvec3(0, 0, 10));
    EXPECT_NEAR(glm::dot(view.forward, glm::dvec3(0, 0, -1)), 1.0, 1e-12);
    // Linear depth is distance along the axis: the near face at 9, the far at 11.
    EXPECT_NEAR(view.nearDepth, 9.0, 1e-9);
    EXPECT_NEAR(view.farDepth, 11.0, 1e-9);
    // Tight: a corner of the near face, at tan = 1 / 9, is within a texel of the edge.
    const double tanHalf = 1.0 / view.projection[0][0];
    EXPECT_NEAR(tanHalf, (1.0 / 9.0) * 512.0 / 510.0, 1e-9);
}

TEST(ShadowLightView, ALightInsideOrTouchingTheBoundsFallsBackWithAReason) {
    const CasterBounds bounds = box({-1, -1, -1}, {1, 1, 1});
    for (glm::vec3 position : {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(1.0f, 1.0f, 1.0f),
                               glm::vec3(0, 0, 1.05f)}) {
        ShadowLightView view = fitShadowLightView(local(position), bounds, 64);
        EXPECT_FALSE(view.valid) << position.x << " " << position.z;
        EXPECT_NE(view.fallback.find("inside or too close"), std::string::npos) << view.fallback;
    }
}

TEST(ShadowLightView, ANarrowSpotInsideTheBoundsLooksAlongItsAxis) {
    ShadingLight spot = local({0, 0, 0});
    spot.shaped = true;
    spot.coneCosOuter = float(std::cos(glm::radians(30.0)));
    spot.emissionAxis = glm::vec3(0, -1, 0);
    ShadowLightView view = fitShadowLightView(spot, box({-1, -1, -1}, {1, 1, 1}), 128);
    ASSERT_TRUE(view.valid) << view.fallback;
    EXPECT_NEAR(glm::dot(view.forward, glm::dvec3(0, -1, 0)), 1.0, 1e-12);
    EXPECT_NEAR(1.0 / view.projection[0][0], std::tan(glm::radians(30.0)) * 128.0 / 126.0, 1e-7);
    EXPECT_GT(view.nearDepth, 0.0);
    EXPECT_NEAR(view.farDepth, 1.0, 1e-9);
}

TEST(ShadowLightView, BadInputIsRefusedNeverAWrongView) {
    const CasterBounds bounds = box({-1, -1, -1}, {1, 1, 1});
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const float nanf = std::numeric_limits<float>::quiet_NaN();
    EXPECT_NE(fitShadowLightView(local({nanf, 0, 5}), bounds, 64).fallback.find("not finite"), std::string::npos);
    EXPECT_NE(fitShadowLightView(distant({0, 1, 0}), box({nan, 0, 0}, {1, 1, 1}), 64).fallback.find("not finite"),
              std::string::npos);
    ShadingLight nowhere;
    nowhere.directionOrPosition = glm::vec3(0.0f);
    EXPECT_FALSE(fitShadowLightView(nowhere, bounds, 64).valid);
    EXPECT_FALSE(fitShadowLightView(distant({0, 1, 0}), CasterBounds{}, 64).valid);
    // Infinite widths are ignored, not spread over the view.
    ShadowLightView wide = fitShadowLightView(distant({0, 1, 0}), box({-1, 0, -1}, {1, 0, 1}, INFINITY), 64);
    EXPECT_TRUE(wide.valid);
}

TEST(ShadowLightView, OneStrandOrAPointStillGetsAFiniteView) {
    // A single straight strand along the light, and a single point: a
    // window and a depth range that are not zero.
    for (const CasterBounds& bounds : {box({0, 0, 0}, {0, 2, 0}, 0.01), box({1, 2, 3}, {1, 2, 3}, 0.0)}) {
        ShadowLightView view = fitShadowLightView(distant({0, 1, 0}), bounds, 32);
        expectHoldsEveryCorner(view, bounds);
        EXPECT_GT(view.texelSize, 0.0);
        EXPECT_GT(view.farDepth, view.nearDepth);
    }
}
