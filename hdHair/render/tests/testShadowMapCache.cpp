// Which shadow maps a frame rebuilds (ShadowMapCache.h) and the deep opacity
// layer boundaries (DeepOpacityLayers.h): both decided on the CPU. That a
// camera move keeps the maps is checked on whole frames (testShadows,
// Shadows.MovingOnlyTheCameraKeepsEveryMapButTheCameraLights).

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "hdHair/plan/DeepOpacityLayers.h"
#include "hdHair/render/ShadowMapCache.h"

using namespace hdhair;

namespace {

CasterBounds unitBox() {
    CasterBounds bounds;
    bounds.min = glm::dvec3(-1.0);
    bounds.max = glm::dvec3(1.0);
    return bounds;
}

ShadowMapRequest request(const std::string& key, glm::vec3 towardsLight) {
    ShadingLight light;
    light.directionOrPosition = glm::normalize(towardsLight);
    return {key, fitShadowLightView(light, unitBox(), 64), false, ShadowLightView{}};
}

// The shadow plan the cache keys its maps by, and one with other maps.
ShadowPlan shadowPlan(int layers = 3) {
    ShadowPlan plan;
    plan.mode = ShadowMode::DeepOpacity;
    plan.layers = layers;
    return plan;
}

}  // namespace

TEST(ShadowMapCache, APlanKeysTheMapsByWhatShapesThemAlone) {
    const ShadowPlan plan = shadowPlan();
    ShadowPlan lookupOnly = plan;
    lookupOnly.bilinear = !plan.bilinear;  // how the maps are read, not drawn
    lookupOnly.lights.push_back(PlannedShadow{});
    lookupOnly.capacity = 8;
    EXPECT_EQ(plan, lookupOnly);
    ShadowPlan tessellated = plan;
    tessellated.pixelsPerSegment = 2.0;
    EXPECT_NE(plan, tessellated);
    ShadowPlan mipmapped = plan;
    mipmapped.convolvedOpacity = true;  // reallocates the opacity layers
    EXPECT_NE(plan, mipmapped);
    EXPECT_NE(plan, shadowPlan(7));
}

TEST(ShadowMapCache, OnlyWhatChangedIsRebuilt) {
    const ShadowPlan s = shadowPlan(), t = shadowPlan(7);
    ShadowMapCache cache;
    std::vector<ShadowMapRequest> lights = {request("/key", {0, 1, 0}), request("/fill", {1, 0, 1})};
    ShadowFrame first = cache.update(lights, s, 1, false);
    ASSERT_EQ(first.maps.size(), 2u);
    EXPECT_TRUE(first.maps[0].rebuild && first.maps[1].rebuild);
    EXPECT_NE(first.maps[0].slot, first.maps[1].slot);
    EXPECT_GE(first.capacity, 2);

    // Nothing changed: both kept, in their slots.
    ShadowFrame same = cache.update(lights, s, 1, false);
    EXPECT_FALSE(same.maps[0].rebuild);
    EXPECT_FALSE(same.maps[1].rebuild);
    EXPECT_EQ(same.maps[0].slot, first.maps[0].slot);
    EXPECT_EQ(same.maps[0].reason.rfind("kept", 0), 0u);

    // One light moves: its map alone.
    lights[1] = request("/fill", {1, 0.2f, 1});
    ShadowFrame moved = cache.update(lights, s, 1, false);
    EXPECT_FALSE(moved.maps[0].rebuild);
    EXPECT_TRUE(moved.maps[1].rebuild);
    EXPECT_EQ(moved.maps[1].reason, "rebuilt: the light moved");

    // Its meshes' view moves (a mesh moved away from the hair): its map alone.
    lights[0].meshView = lights[1].view;
    ShadowFrame meshMoved = cache.update(lights, s, 1, false);
    EXPECT_TRUE(meshMoved.maps[0].rebuild);
    EXPECT_FALSE(meshMoved.maps[1].rebuild);

    // The hair or the settings change: all of them.
    ShadowFrame hair = cache.update(lights, s, 2, false);
    EXPECT_TRUE(hair.maps[0].rebuild && hair.maps[1].rebuild);
    EXPECT_EQ(hair.maps[0].reason, "rebuilt: the hair changed");
    ShadowFrame settings = cache.update(lights, t, 2, false);
    EXPECT_TRUE(settings.maps[0].rebuild && settings.maps[1].rebuild);

    // Sharing one pool (the reference): one change rebuilds all.
    lights[0] = request("/key", {0.1f, 1, 0});
    ShadowFrame together = cache.update(lights, t, 2, true);
    EXPECT_TRUE(together.maps[0].rebuild && together.maps[1].rebuild);
}

TEST(ShadowMapCache, NewLightsTakeFreeSlotsAndGrowingStorageRebuildsAll) {
    const ShadowPlan s = shadowPlan();
    ShadowMapCache cache;
    std::vector<ShadowMapRequest> lights = {request("/a", {0, 1, 0})};
    EXPECT_EQ(cache.update(lights, s, 1, false).capacity, 1);
    lights.push_back(request("/b", {1, 1, 0}));
    ShadowFrame grown = cache.update(lights, s, 1, false);
    EXPECT_EQ(grown.capacity, 2);
    EXPECT_EQ(grown.maps[0].reason, "rebuilt: the map storage grew to 2 lights");
    // /a goes: its slot is free for /c, with no growth and /b kept.
    lights = {request("/b", {1, 1, 0}), request("/c", {0, 1, 1})};
    ShadowFrame swapped = cache.update(lights, s, 1, false);
    EXPECT_EQ(swapped.capacity, 2);
    EXPECT_FALSE(swapped.maps[0].rebuild);
    EXPECT_EQ(swapped.maps[1].slot, grown.maps[0].slot);
    // A map that could not be built is forgotten and built again.
    cache.forget("/b");
    EXPECT_TRUE(cache.update(lights, s, 1, false).maps[0].rebuild);
}

TEST(DeepOpacityLayers, LinearSpacingGrowsItsGapsLinearly) {
    const std::vector<float> layers = deepOpacityLayerBoundaries(4, ShadowLayerSpacing::Linear);
    ASSERT_EQ(layers.size(), 4u);
    // Gaps 1, 2, 3, 4 tenths.
    const float expected[4] = {0.1f, 0.3f, 0.6f, 1.0f};
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(layers[size_t(k)], expected[k], 1e-6f) << k;
    const std::vector<float> uniform = deepOpacityLayerBoundaries(4, ShadowLayerSpacing::Uniform);
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(uniform[size_t(k)], 0.25f * float(k + 1), 1e-6f) << k;
    EXPECT_EQ(deepOpacityLayerBoundaries(1, ShadowLayerSpacing::Linear), std::vector<float>{1.0f});
    EXPECT_EQ(deepOpacityLayerBoundaries(99, ShadowLayerSpacing::Linear).size(), size_t(kMaxShadowLayers));
}
