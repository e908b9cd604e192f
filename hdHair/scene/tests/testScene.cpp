#include <gtest/gtest.h>

#include "hdHair/scene/Scene.h"

using namespace hdhair;

TEST(Scene, AddChangeRemoveOnePrimAtATime) {
    Scene scene;
    CurvesPrim curves;
    curves.path = "/World/hair";
    curves.curveVertexCounts = {4};
    scene.setCurves(curves);
    ASSERT_EQ(scene.curves().size(), 1u);
    uint64_t first = scene.curves().at("/World/hair").version;

    curves.curveVertexCounts = {5};
    scene.setCurves(curves);
    EXPECT_GT(scene.curves().at("/World/hair").version, first);
    EXPECT_EQ(scene.findCurves("/World/hair")->curveVertexCounts[0], 5);

    EXPECT_TRUE(scene.remove("/World/hair"));
    EXPECT_FALSE(scene.remove("/World/hair"));
    EXPECT_TRUE(scene.curves().empty());
}

TEST(Scene, SnapshotsOutliveReplacement) {
    Scene scene;
    CurvesPrim curves;
    curves.path = "/a";
    curves.points = {glm::vec3(1.0f)};
    scene.setCurves(curves);
    std::shared_ptr<const CurvesPrim> held = scene.curves().at("/a").prim;
    curves.points = {glm::vec3(2.0f)};
    scene.setCurves(curves);
    EXPECT_EQ(held->points[0].x, 1.0f);
    EXPECT_EQ(scene.findCurves("/a")->points[0].x, 2.0f);
}

TEST(Scene, PathNamesOnePrimWhateverItsKind) {
    Scene scene;
    CurvesPrim curves;
    curves.path = "/x";
    scene.setCurves(curves);
    LightPrim light;
    light.path = "/x";
    scene.setLight(light);
    EXPECT_TRUE(scene.curves().empty());
    EXPECT_EQ(scene.lights().size(), 1u);
}

TEST(Scene, VersionsAreNeverReusedAcrossScenes) {
    // The renderer caches prepared curves by path and version across scenes.
    CurvesPrim curves;
    curves.path = "/World/hair";
    Scene first, second;
    first.setCurves(curves);
    second.setCurves(curves);
    EXPECT_NE(first.curves().at("/World/hair").version, second.curves().at("/World/hair").version);
}

TEST(Scene, SubsetKeepsVersions) {
    Scene scene;
    CurvesPrim a, b;
    a.path = "/a";
    b.path = "/b";
    scene.setCurves(a);
    scene.setCurves(b);
    Scene onlyB = scene.subset([](const std::string& path) { return path == "/b"; });
    ASSERT_EQ(onlyB.curves().size(), 1u);
    EXPECT_EQ(onlyB.curves().at("/b").version, scene.curves().at("/b").version);
    EXPECT_EQ(onlyB.curves().at("/b").prim, scene.curves().at("/b").prim);
}

TEST(Scene, MaterialsAreFoundByPathWithTheirVersions) {
    Scene scene;
    EXPECT_EQ(scene.findMaterial(""), nullptr);
    MaterialPrim material;
    material.path = "/Looks/hair";
    material.surfaceShaderId = "UsdPreviewSurface";
    scene.setMaterial(material);
    const SceneEntry<MaterialPrim>* found = scene.findMaterial("/Looks/hair");
    ASSERT_NE(found, nullptr);
    const uint64_t first = found->version;
    material.diffuseColor.value = {1.0f, 0.0f, 0.0f};
    scene.setMaterial(material);
    EXPECT_GT(scene.findMaterial("/Looks/hair")->version, first);
    EXPECT_EQ(scene.subset([](const std::string&) { return true; }).materials().size(), 1u);
    EXPECT_TRUE(scene.remove("/Looks/hair"));
    EXPECT_EQ(scene.findMaterial("/Looks/hair"), nullptr);
}

TEST(Scene, SettingAnEqualPrimKeepsItsVersion) {
    Scene scene;
    CurvesPrim curves;
    curves.path = "/a";
    curves.points = {glm::vec3(1.0f)};
    curves.primvars["widths"].values = {0.1f};
    scene.setCurves(curves);
    const uint64_t version = scene.curves().at("/a").version, sceneVersion = scene.version();
    scene.setCurves(curves);
    EXPECT_EQ(scene.curves().at("/a").version, version);
    EXPECT_EQ(scene.version(), sceneVersion);
    // Any member, primvars included, is a change.
    curves.primvars["widths"].values = {0.2f};
    scene.setCurves(curves);
    EXPECT_GT(scene.curves().at("/a").version, version);

    LightPrim light;
    light.path = "/key";
    scene.setLight(light);
    const uint64_t lightVersion = scene.lights().at("/key").version;
    scene.setLight(light);
    EXPECT_EQ(scene.lights().at("/key").version, lightVersion);
    light.intensity = 2.0f;
    scene.setLight(light);
    EXPECT_GT(scene.lights().at("/key").version, lightVersion);
    // Turning its shadows off is a change too (fields() must list it).
    const uint64_t litVersion = scene.lights().at("/key").version;
    light.shadowEnable = false;
    scene.setLight(light);
    EXPECT_GT(scene.lights().at("/key").version, litVersion);
}

TEST(Scene, UpdateFromKeepsUnchangedPrimsAndDropsMissingOnes) {
    auto frameAt = [](float y, bool withLight) {
        Scene scene;
        CurvesPrim still, moving;
        still.path = "/still";
        still.points = {glm::vec3(0.0f)};
        moving.path = "/moving";
        moving.points = {glm::vec3(0.0f, y, 0.0f)};
        scene.setCurves(still);
        scene.setCurves(moving);
        if (withLight) {
            LightPrim light;
            light.path = "/key";
            scene.setLight(light);
        }
        scene.info().endTimeCode = y;
        return scene;
    };
    Scene scene;
    scene.updateFrom(frameAt(1.0f, true));
    const uint64_t still = scene.curves().at("/still").version, moving = scene.curves().at("/moving").version;
    scene.updateFrom(frameAt(2.0f, false));
    EXPECT_EQ(scene.curves().at("/still").version, still);
    EXPECT_GT(scene.curves().at("/moving").version, moving);
    EXPECT_EQ(scene.findCurves("/moving")->points[0].y, 2.0f);
    EXPECT_TRUE(scene.lights().empty());
    EXPECT_EQ(scene.info().endTimeCode, 2.0);
}
