// Lights are shaded at most lightsPerPass at a time; each batch draws the
// same sorted strands and the batches' colours are summed with alpha counted
// once (Svoboda 2012, section 2.5.3). The image must not depend on how the
// lights are split, with or without transparency.

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "StageRendering.h"
#include "hdHair/image/ImageComparison.h"
#include "hdHair/plan/CameraView.h"
#include "hdHair/scene/Scene.h"
#include "hdHair/usda/SceneReader.h"

using namespace hdhair;
using namespace hdhair::testenv;

namespace {

constexpr double kOneStep = 1.0 / 255.0;

struct LitStage {
    Scene scene;
    CameraView camera;
};

// The wavy example without its own lights, and `lights` distant lights of
// different directions and colours (plus a dome, so the ambient term is
// exercised too).
LitStage litStage(int lights, float intensity = 0.6f) {
    LitStage stage;
    Diagnostics diagnostics;
    usda::readSceneFile(sourcePath("examples/wavy_strands.usda"), 0.0, stage.scene, diagnostics);
    std::vector<std::string> stageLights;
    for (const auto& [path, entry] : stage.scene.lights()) stageLights.push_back(path);
    for (const std::string& path : stageLights) stage.scene.remove(path);
    for (int i = 0; i < lights; ++i) {
        LightPrim light;
        light.path = "/Lights/distant" + std::to_string(i);
        light.type = LightType::Distant;
        light.intensity = intensity;
        light.color = glm::vec3(0.5f + 0.5f * std::sin(float(i)), 0.7f, 0.5f + 0.5f * std::cos(float(i)));
        light.worldTransform = glm::rotate(glm::rotate(glm::dmat4(1.0), 0.7 * i, glm::dvec3(0, 1, 0)),
                                           -0.3 - 0.1 * i, glm::dvec3(1, 0, 0));
        stage.scene.setLight(light);
    }
    LightPrim dome;
    dome.path = "/Lights/dome";
    dome.type = LightType::Dome;
    dome.intensity = 0.05f;
    stage.scene.setLight(dome);
    stage.camera = cameraViewFromPrim(*stage.scene.findCamera("/World/main_cam"), 192);
    return stage;
}

RenderResult render(const LitStage& stage, std::vector<std::string> assignments) {
    RenderSettings settings;
    for (const std::string& assignment : assignments) settings.setFromAssignment(assignment);
    Diagnostics diagnostics;
    RenderResult result = sharedRenderer().render(stage.scene, stage.camera, settings, diagnostics);
    EXPECT_TRUE(diagnostics.warnings().empty());
    return result;
}

}  // namespace

class LightBatching : public ::testing::TestWithParam<const char*> {};

TEST_P(LightBatching, ImageDoesNotDependOnHowLightsAreSplit) {
    std::string transparency = std::string("transparency=") + GetParam();
    for (int lights : {1, 4, 5, 9}) {
        LitStage stage = litStage(lights);
        Image allAtOnce = render(stage, {transparency, "lightsPerPass=16"}).color;
        for (int perPass : {1, 2, 4}) {
            RenderResult batched = render(stage, {transparency, "lightsPerPass=" + std::to_string(perPass)});
            EXPECT_EQ(batched.stats.lightPasses, size_t((lights + perPass - 1) / perPass));
            ImageComparison comparison = compareImages(batched.color, allAtOnce, exactWithin(kOneStep));
            EXPECT_TRUE(comparison.passed)
                << lights << " lights, " << perPass << " per pass: " << comparison.description;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Transparency, LightBatching, ::testing::Values("binSorted", "opaque", "exact"));

// A flat prim next to lit ones: its displayColor belongs to the first batch
// only, so five lights one at a time give the image of all five at once.
TEST(LightBatchingExtra, FlatPrimsAreCountedOnceAcrossBatches) {
    LitStage stage = litStage(5);
    const std::string flatPath = stage.scene.curves().begin()->first;
    CurvesPrim flat = *stage.scene.curves().begin()->second.prim;
    flat.shadingModel = "flat";
    stage.scene.setCurves(flat);
    for (const char* transparency : {"transparency=binSorted", "transparency=opaque", "transparency=exact"}) {
        Image allAtOnce = render(stage, {transparency, "lightsPerPass=16"}).color;
        RenderResult batched = render(stage, {transparency, "lightsPerPass=1"});
        EXPECT_EQ(batched.stats.lightPasses, 5u);
        ImageComparison comparison = compareImages(batched.color, allAtOnce, exactWithin(kOneStep));
        EXPECT_TRUE(comparison.passed) << transparency << ", flat " << flatPath << ": " << comparison.description;
    }
}

TEST(LightBatchingExtra, ALightOfZeroIntensityChangesNothing) {
    LitStage stage = litStage(4);
    Image before = render(stage, {}).color;
    LightPrim dark;
    dark.path = "/Lights/dark";
    dark.intensity = 0.0f;
    stage.scene.setLight(dark);  // now 5 lights: two passes
    RenderResult after = render(stage, {});
    EXPECT_EQ(after.stats.lightPasses, 2u);
    ImageComparison comparison = compareImages(after.color, before, exactWithin(1e-6));
    EXPECT_TRUE(comparison.passed) << comparison.description;
}

TEST(LightUnits, DoublingIntensityDoublesLinearOutputAndOneStopOfExposureEqualsIt) {
    LitStage single = litStage(1, 1.0f);
    single.scene.remove("/Lights/dome");
    Image base = render(single, {"transparency=opaque"}).color;
    LitStage doubled = litStage(1, 2.0f);
    doubled.scene.remove("/Lights/dome");
    Image twice = render(doubled, {"transparency=opaque"}).color;
    LitStage exposed = litStage(1, 1.0f);
    exposed.scene.remove("/Lights/dome");
    LightPrim light = *exposed.scene.lights().at("/Lights/distant0").prim;
    light.exposure = 1.0f;
    exposed.scene.setLight(light);
    Image exposure = render(exposed, {"transparency=opaque"}).color;
    double largest = 0.0;
    for (size_t p = 0; p < base.pixels.size(); ++p) {
        if (p % 4 == 3) continue;  // alpha is coverage, not light
        EXPECT_NEAR(twice.pixels[p], 2.0f * base.pixels[p], 1e-5f + 1e-5f * base.pixels[p]);
        EXPECT_NEAR(exposure.pixels[p], twice.pixels[p], 1e-5f + 1e-5f * twice.pixels[p]);
        largest = std::max(largest, double(base.pixels[p]));
    }
    EXPECT_GT(largest, 0.01) << "the stage must actually be lit";
}
