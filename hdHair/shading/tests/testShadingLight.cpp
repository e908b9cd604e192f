#include <algorithm>
#include <cmath>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "hdHair/shading/ColorTemperature.h"
#include "hdHair/shading/ShadingLight.h"

using namespace hdhair;

TEST(ShadingLight, DistantLightShinesFromItsPlusZAxis) {
    LightPrim light;
    light.type = LightType::Distant;
    light.intensity = 2.0f;
    // Rotate -90 degrees about X: the light's -Z (emission) turns to -Y, so it shines down.
    light.worldTransform = glm::rotate(glm::dmat4(1.0), -glm::half_pi<double>(), glm::dvec3(1, 0, 0));
    ShadingLights lights = toShadingLights({&light});
    ASSERT_EQ(lights.lights.size(), 1u);
    glm::vec3 towards;
    glm::vec3 e = irradianceAt(lights.lights[0], glm::vec3(5.0f), &towards);
    EXPECT_NEAR(towards.y, 1.0f, 1e-6f);
    EXPECT_NEAR(e.r, 2.0f, 1e-6f);
}

TEST(ShadingLight, ExposureDoublesPerStop) {
    LightPrim light;
    light.intensity = 3.0f;
    light.exposure = 1.0f;
    light.color = glm::vec3(1.0f, 0.5f, 0.25f);
    glm::vec3 radiance = lightRadiance(light);
    EXPECT_FLOAT_EQ(radiance.r, 6.0f);
    EXPECT_FLOAT_EQ(radiance.g, 3.0f);
    EXPECT_FLOAT_EQ(radiance.b, 1.5f);
}

TEST(ShadingLight, SphereLightFallsOffWithSquaredDistance) {
    LightPrim light;
    light.type = LightType::Sphere;
    light.radius = 0.5f;
    light.intensity = 1.0f;
    light.worldTransform = glm::translate(glm::dmat4(1.0), glm::dvec3(0, 10, 0));
    ShadingLight shading = toShadingLights({&light}).lights.at(0);
    glm::vec3 towards;
    glm::vec3 near = irradianceAt(shading, {0, 8, 0}, &towards);   // d = 2
    glm::vec3 far = irradianceAt(shading, {0, 6, 0}, &towards);    // d = 4
    EXPECT_NEAR(near.r, glm::pi<float>() * 0.25f / 4.0f, 1e-6f);
    EXPECT_NEAR(near.r / far.r, 4.0f, 1e-4f);
    EXPECT_NEAR(towards.y, 1.0f, 1e-6f);
    glm::vec3 atCentre = irradianceAt(shading, {0, 10, 0}, &towards);  // d = 0: finite
    EXPECT_TRUE(std::isfinite(atCentre.r) && std::isfinite(towards.x));
}

TEST(ShadingLight, RectLightIsOneSided) {
    LightPrim light;
    light.type = LightType::Rect;
    light.worldTransform = glm::translate(glm::dmat4(1.0), glm::dvec3(0, 0, 5));  // emits towards -Z
    ShadingLight shading = toShadingLights({&light}).lights.at(0);
    glm::vec3 towards;
    EXPECT_GT(irradianceAt(shading, {0, 0, 0}, &towards).r, 0.0f);
    EXPECT_EQ(irradianceAt(shading, {0, 0, 10}, &towards).r, 0.0f);
}

TEST(ShadingLight, DomeLightBecomesAmbientAndInvisibleLightsAreSkipped) {
    LightPrim dome;
    dome.type = LightType::Dome;
    dome.intensity = 0.5f;
    LightPrim hidden;
    hidden.visible = false;
    ShadingLights lights = toShadingLights({&dome, &hidden});
    EXPECT_TRUE(lights.lights.empty());
    EXPECT_FLOAT_EQ(lights.ambient.g, 0.5f);
}

// --- Colour temperature -----------------------------------------------------

namespace {

float luminance(const glm::vec3& rgb) { return 0.2126f * rgb.r + 0.7152f * rgb.g + 0.0722f * rgb.b; }

// Chromaticity (x, y) of linear Rec.709 RGB, through the Rec.709 / sRGB to
// CIE XYZ matrix (D65).
glm::dvec2 chromaticity(const glm::vec3& rgb) {
    double X = 0.4124564 * rgb.r + 0.3575761 * rgb.g + 0.1804375 * rgb.b;
    double Y = 0.2126729 * rgb.r + 0.7151522 * rgb.g + 0.0721750 * rgb.b;
    double Z = 0.0193339 * rgb.r + 0.1191920 * rgb.g + 0.9503041 * rgb.b;
    return {X / (X + Y + Z), Y / (X + Y + Z)};
}

// The Planckian locus by Kim et al.'s cubic spline (US patent 7,024,034,
// 2006), valid from 1667 K to 25000 K: an approximation independent of the
// one under test.
glm::dvec2 planckianLocus(double t) {
    double x = t <= 4000.0 ? -0.2661239e9 / (t * t * t) - 0.2343589e6 / (t * t) + 0.8776956e3 / t + 0.179910
                           : -3.0258469e9 / (t * t * t) + 2.1070379e6 / (t * t) + 0.2226347e3 / t + 0.240390;
    double y = t <= 2222.0   ? -1.1063814 * x * x * x - 1.34811020 * x * x + 2.18555832 * x - 0.20219683
               : t <= 4000.0 ? -0.9549476 * x * x * x - 1.37418593 * x * x + 2.09137015 * x - 0.16748867
                             : 3.0817580 * x * x * x - 5.87338670 * x * x + 3.75112997 * x - 0.37001483;
    return {x, y};
}

}  // namespace

TEST(ColorTemperature, DisabledLeavesTheColourUnchanged) {
    LightPrim light;
    light.color = glm::vec3(0.2f, 0.5f, 0.8f);
    light.colorTemperature = 2000.0f;
    light.enableColorTemperature = false;
    glm::vec3 radiance = lightRadiance(light);
    EXPECT_FLOAT_EQ(radiance.r, 0.2f);
    EXPECT_FLOAT_EQ(radiance.g, 0.5f);
    EXPECT_FLOAT_EQ(radiance.b, 0.8f);
}

TEST(ColorTemperature, EnabledMultipliesTheColour) {
    LightPrim light;
    light.intensity = 2.0f;
    light.color = glm::vec3(0.5f, 1.0f, 0.25f);
    light.enableColorTemperature = true;
    light.colorTemperature = 3000.0f;
    glm::vec3 blackbody = blackbodyColor(3000.0f);
    glm::vec3 radiance = lightRadiance(light);
    EXPECT_FLOAT_EQ(radiance.r, 2.0f * 0.5f * blackbody.r);
    EXPECT_FLOAT_EQ(radiance.g, 2.0f * 1.0f * blackbody.g);
    EXPECT_FLOAT_EQ(radiance.b, 2.0f * 0.25f * blackbody.b);
}

// A 6500 K blackbody lies slightly below D65 on the chromaticity diagram, so
// it is white only to within a few percent (UsdLux's own table gives
// (1.043, 0.984, 1.035) after normalisation).
TEST(ColorTemperature, SixtyFiveHundredKelvinIsAlmostWhite) {
    glm::vec3 c = blackbodyColor(6500.0f);
    EXPECT_NEAR(c.r, 1.0f, 0.05f);
    EXPECT_NEAR(c.g, 1.0f, 0.05f);
    EXPECT_NEAR(c.b, 1.0f, 0.05f);
}

TEST(ColorTemperature, LowTemperaturesAreReddishHighOnesBluish) {
    glm::vec3 warm = blackbodyColor(2000.0f);
    EXPECT_GT(warm.r, warm.g);
    EXPECT_GT(warm.g, warm.b);
    glm::vec3 cool = blackbodyColor(10000.0f);
    EXPECT_GT(cool.b, cool.g);
    EXPECT_GT(cool.g, cool.r);
    // Red falls and blue rises steadily with temperature.
    glm::vec3 previous = blackbodyColor(1000.0f);
    for (float t = 1250.0f; t <= 10000.0f; t += 250.0f) {
        glm::vec3 c = blackbodyColor(t);
        EXPECT_LT(c.r, previous.r) << t;
        EXPECT_GE(c.b, previous.b) << t;
        previous = c;
    }
}

TEST(ColorTemperature, LuminanceIsOneAtEveryTemperature) {
    for (float t = 1000.0f; t <= 10000.0f; t += 100.0f) {
        glm::vec3 c = blackbodyColor(t);
        EXPECT_NEAR(luminance(c), 1.0f, 1e-5f) << t;
        EXPECT_GE(std::min({c.r, c.g, c.b}), 0.0f) << t;
    }
}

TEST(ColorTemperature, FollowsThePlanckianLocus) {
    for (double t : {2000.0, 2500.0, 3000.0, 4000.0, 5000.0, 6500.0, 8000.0, 10000.0}) {
        glm::dvec2 expected = planckianLocus(t);
        glm::dvec2 actual = chromaticity(blackbodyColor(float(t)));
        EXPECT_NEAR(actual.x, expected.x, 0.004) << t;
        EXPECT_NEAR(actual.y, expected.y, 0.004) << t;
    }
}

TEST(ColorTemperature, ClampsToTheSupportedRange) {
    glm::vec3 low = blackbodyColor(kMinColorTemperature), high = blackbodyColor(kMaxColorTemperature);
    glm::vec3 below = blackbodyColor(200.0f), above = blackbodyColor(40000.0f);
    EXPECT_EQ(below, low);
    EXPECT_EQ(above, high);
    glm::vec3 nan = blackbodyColor(std::nanf(""));
    EXPECT_EQ(nan, blackbodyColor(6500.0f));
}

// --- Spot shaping -----------------------------------------------------------

namespace {

// A sphere light at the origin, shining down -Z, with a cone.
ShadingLight spotLight(float coneAngle, float coneSoftness) {
    LightPrim light;
    light.type = LightType::Sphere;
    light.coneAngle = coneAngle;
    light.coneSoftness = coneSoftness;
    return toShadingLights({&light}).lights.at(0);
}

// A point at distance 2 from the origin, `degrees` off the -Z axis.
glm::vec3 offAxis(float degrees) {
    float a = glm::radians(degrees);
    return 2.0f * glm::vec3(std::sin(a), 0.0f, -std::cos(a));
}

float irradianceR(const ShadingLight& light, const glm::vec3& position) {
    glm::vec3 towards;
    return irradianceAt(light, position, &towards).r;
}

}  // namespace

TEST(SpotShaping, HardConeCutsOffAtItsAngle) {
    ShadingLight spot = spotLight(30.0f, 0.0f);
    ShadingLight unshaped = spotLight(90.0f, 0.0f);
    EXPECT_TRUE(spot.shaped);
    float full = irradianceR(unshaped, offAxis(0.0f));
    EXPECT_GT(full, 0.0f);
    EXPECT_FLOAT_EQ(irradianceR(spot, offAxis(0.0f)), full);   // on the axis
    EXPECT_FLOAT_EQ(irradianceR(spot, offAxis(25.0f)), full);  // inside
    EXPECT_EQ(irradianceR(spot, offAxis(45.0f)), 0.0f);        // outside
    EXPECT_EQ(irradianceR(spot, -offAxis(0.0f)), 0.0f);        // behind
}

// Softness fades the light in from the cone's edge inwards: the angle stays
// the outer limit, full light only within angle * (1 - softness).
TEST(SpotShaping, SoftnessFadesInsideTheCone) {
    ShadingLight soft = spotLight(30.0f, 0.5f);
    float full = irradianceR(spotLight(90.0f, 0.0f), offAxis(0.0f));
    EXPECT_FLOAT_EQ(irradianceR(soft, offAxis(0.0f)), full);
    EXPECT_FLOAT_EQ(irradianceR(soft, offAxis(10.0f)), full);  // within 15 degrees
    EXPECT_EQ(irradianceR(soft, offAxis(45.0f)), 0.0f);
    float edge = irradianceR(soft, offAxis(25.0f));
    EXPECT_GT(edge, 0.0f);
    EXPECT_LT(edge, full);
    // smoothstep(cos 30, cos 15, cos 25)
    double t = (std::cos(glm::radians(25.0)) - std::cos(glm::radians(30.0))) /
               (std::cos(glm::radians(15.0)) - std::cos(glm::radians(30.0)));
    EXPECT_NEAR(edge / full, t * t * (3.0 - 2.0 * t), 1e-4);
    // The fade is monotonic from the inner angle to the cone's edge.
    float previous = full;
    for (float degrees = 15.0f; degrees <= 30.0f; degrees += 1.0f) {
        float e = irradianceR(soft, offAxis(degrees));
        EXPECT_LE(e, previous + 1e-6f) << degrees;
        previous = e;
    }
    EXPECT_NEAR(irradianceR(soft, offAxis(29.99f)), 0.0f, 1e-4f * full);
    // Full softness fades from the axis itself.
    float fullySoft = irradianceR(spotLight(30.0f, 1.0f), offAxis(15.0f));
    EXPECT_GT(fullySoft, 0.0f);
    EXPECT_LT(fullySoft, full);
}

TEST(SpotShaping, NinetyDegreesAndMoreLeaveTheLightUnshaped) {
    for (float angle : {90.0f, 120.0f, 180.0f}) {
        ShadingLight light = spotLight(angle, 0.5f);
        EXPECT_FALSE(light.shaped) << angle;
        EXPECT_GT(irradianceR(light, -offAxis(0.0f)), 0.0f) << angle;  // a sphere light lights behind it
    }
    LightPrim distant;
    distant.coneAngle = 10.0f;  // distant lights are never shaped
    EXPECT_FALSE(toShadingLights({&distant}).lights.at(0).shaped);
}

TEST(SpotShaping, ConeFollowsTheLightsTransform) {
    LightPrim light;
    light.type = LightType::Disk;
    light.coneAngle = 20.0f;
    // Rotate -90 degrees about X: the light's -Z turns to -Y, so it shines down.
    light.worldTransform = glm::translate(glm::dmat4(1.0), glm::dvec3(0, 10, 0)) *
                           glm::rotate(glm::dmat4(1.0), -glm::half_pi<double>(), glm::dvec3(1, 0, 0));
    ShadingLight spot = toShadingLights({&light}).lights.at(0);
    EXPECT_GT(irradianceR(spot, {0, 0, 0}), 0.0f);  // straight below
    EXPECT_EQ(irradianceR(spot, {5, 0, 0}), 0.0f);  // 26.6 degrees off the axis
    EXPECT_GT(irradianceR(spot, {3, 0, 0}), 0.0f);  // 16.7 degrees off the axis
}

// --- Light units --------------------------------------------------------------

TEST(LightUnits, IrradianceIsProportionalToIntensity) {
    LightPrim light;
    light.type = LightType::Sphere;
    light.coneAngle = 30.0f;
    light.coneSoftness = 0.3f;
    light.enableColorTemperature = true;
    light.colorTemperature = 4000.0f;
    glm::vec3 position = offAxis(20.0f);
    glm::vec3 towards;
    glm::vec3 once = irradianceAt(toShadingLights({&light}).lights.at(0), position, &towards);
    light.intensity = 2.0f;
    glm::vec3 twice = irradianceAt(toShadingLights({&light}).lights.at(0), position, &towards);
    EXPECT_GT(once.r, 0.0f);
    for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(twice[c], 2.0f * once[c]);
}

TEST(LightUnits, OneStopOfExposureDoublesIntensity) {
    for (LightType type : {LightType::Distant, LightType::Sphere, LightType::Rect, LightType::Disk}) {
        LightPrim doubled;
        doubled.type = type;
        doubled.intensity = 3.0f;
        doubled.worldTransform = glm::translate(glm::dmat4(1.0), glm::dvec3(0, 0, 4));
        LightPrim exposed = doubled;
        doubled.intensity = 6.0f;
        exposed.exposure = 1.0f;
        glm::vec3 towards;
        glm::vec3 a = irradianceAt(toShadingLights({&doubled}).lights.at(0), {0.5f, 0.0f, 0.0f}, &towards);
        glm::vec3 b = irradianceAt(toShadingLights({&exposed}).lights.at(0), {0.5f, 0.0f, 0.0f}, &towards);
        EXPECT_GT(a.g, 0.0f);
        EXPECT_FLOAT_EQ(a.g, b.g) << toString(type);
    }
}
