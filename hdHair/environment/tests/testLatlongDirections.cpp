#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "hdHair/environment/LatlongDirections.h"

using namespace hdhair;

namespace {

void expectNear(const glm::vec3& actual, const glm::vec3& expected, float tolerance = 1e-6f) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

}  // namespace

// The points UsdLux's DomeLight documentation (the OpenEXR latlong
// convention) and Storm's shaders pin down, by hand: the top row is +Y, the
// centre of the horizon +Z, a quarter across +X, three quarters −X, the
// edges −Z.
TEST(LatlongDirections, StormsOrientation) {
    expectNear(latlongDirection(0.5f, 0.0f), {0, 1, 0});
    expectNear(latlongDirection(0.3f, 1.0f), {0, -1, 0});
    expectNear(latlongDirection(0.5f, 0.5f), {0, 0, 1});
    expectNear(latlongDirection(0.25f, 0.5f), {1, 0, 0});
    expectNear(latlongDirection(0.75f, 0.5f), {-1, 0, 0});
    expectNear(latlongDirection(0.0f, 0.5f), {0, 0, -1});
    expectNear(latlongDirection(1.0f, 0.5f), {0, 0, -1});
    // 45° up, towards +X: u = 1/4, v = 1/4.
    expectNear(latlongDirection(0.25f, 0.25f), {std::sqrt(0.5f), std::sqrt(0.5f), 0});

    const glm::vec2 x = latlongCoordinates({1, 0, 0});
    EXPECT_NEAR(x.x, 0.25f, 1e-6f);
    EXPECT_NEAR(x.y, 0.5f, 1e-6f);
    EXPECT_NEAR(latlongCoordinates({-1, 0, 0}).x, 0.75f, 1e-6f);
    EXPECT_NEAR(latlongCoordinates({0, 0, 2}).x, 0.5f, 1e-6f);  // any length
    EXPECT_NEAR(latlongCoordinates({0, 3, 0}).y, 0.0f, 1e-6f);
    // Storm's own formula, u = (atan(z, x) + π/2) / 2π wrapped, agrees everywhere.
    for (float u = 0.01f; u < 1.0f; u += 0.0731f) {
        const glm::vec3 d = latlongDirection(u, 0.4f);
        float storm = (std::atan2(d.z, d.x) + 0.5f * 3.14159265f) / (2.0f * 3.14159265f);
        if (storm < 0.0f) storm += 1.0f;
        EXPECT_NEAR(storm, u, 1e-5f) << "u = " << u;
    }
}

TEST(LatlongDirections, CoordinatesAndDirectionsRoundTrip) {
    for (float v = 0.05f; v < 1.0f; v += 0.1f) {
        for (float u = 0.0f; u < 1.0f; u += 0.0625f) {
            const glm::vec2 back = latlongCoordinates(latlongDirection(u, v));
            EXPECT_NEAR(back.x, u, 1e-5f) << u << ", " << v;
            EXPECT_NEAR(back.y, v, 1e-5f) << u << ", " << v;
            EXPECT_GE(back.x, 0.0f);
            EXPECT_LT(back.x, 1.0f);
        }
    }
    // −Z from either side lands on u = 0, never on 1.
    EXPECT_EQ(latlongCoordinates({0, 0, -1}).x, 0.0f);
    EXPECT_GE(latlongCoordinates({-1e-7f, 0, -1}).x, 0.0f);
    EXPECT_LT(latlongCoordinates({-1e-7f, 0, -1}).x, 1.0f);
}

// A dome turned 90° about +Y (right-handed: +Z goes to +X) lights from +X
// what it lit from +Z; Storm looks world +X up at the dome's +Z.
TEST(LatlongDirections, TheDomesTransformTurnsItsDirections) {
    const glm::dmat4 turned =
        glm::rotate(glm::translate(glm::dmat4(1.0), glm::dvec3(5, 6, 7)), glm::radians(90.0), glm::dvec3(0, 1, 0));
    expectNear(domeLightDirectionToWorld(turned, {0, 0, 1}), {1, 0, 0});
    expectNear(domeLightDirectionToWorld(turned, {1, 0, 0}), {0, 0, -1});
    expectNear(domeLightDirectionToWorld(turned, {0, 1, 0}), {0, 1, 0});
    expectNear(worldDirectionToDomeLight(turned, {1, 0, 0}), {0, 0, 1});
    // A scaled dome: directions stay unit length.
    const glm::dmat4 scaled = glm::scale(glm::dmat4(1.0), glm::dvec3(2, 2, 2));
    expectNear(domeLightDirectionToWorld(scaled, {0, 0, 1}), {0, 0, 1});
}
