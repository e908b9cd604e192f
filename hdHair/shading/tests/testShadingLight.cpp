#include <cmath>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

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
