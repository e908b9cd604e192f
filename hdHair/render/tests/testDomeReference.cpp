// The SRBF dome lighting (domeLighting=srbf, DomeLighting.h) against its
// reference (domeLighting=sampled: the dome as importance-sampled distant
// lights, each with its own deep opacity map), on a small tuft of wavy,
// translucent strands: the bounds the README states, the mutations the
// comparison must catch (a dome turned, a lobe amplitude scaled, the
// shadows dropped), and the reference's refusal to shade lights unshadowed.
//
// The error is relativeColorError (hdHair/image/ImageComparison.h): RMS of
// the colour difference over covered pixels relative to the reference's RMS,
// and the largest difference relative to the reference's largest value.

#include <cstdlib>
#include <iostream>
#include <stdexcept>
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/environment/tests/LatlongTestTextures.h"
#include "hdHair/image/ImageComparison.h"
#include "hdHair/render/Renderer.h"
#include "hdHair/render/tests/OwnCacheFolderTest.h"
#include "hdHair/render/tests/HairTuft.h"
#include "hdHair/scene/Scene.h"

using namespace hdhair;

namespace {

// The SRBF tables go to a folder of the test's own.
class DomeReference : public test::OwnCacheFolderTest {};

// The sun a little above the horizon towards +Z, the camera's side, and to
// the right: it lights the tuft's front and side, and its shadows fall
// through the tuft.
const glm::vec3 kSun = glm::normalize(glm::vec3(0.6f, 0.35f, 0.7f));

std::string writeSky(const std::string& file) {
    const int width = 256, height = 128;
    test::writeTestImage(file, width, height, 3, test::latlongPixels(width, height, [](const glm::vec3& d) {
                             return test::proceduralSky(d, kSun);
                         }));
    return file;
}

LightPrim dome(const std::string& textureFile, glm::dmat4 transform = glm::dmat4(1.0)) {
    LightPrim light;
    light.path = "/World/dome";
    light.type = LightType::Dome;
    light.textureFile = textureFile;
    light.intensity = 0.5f;
    light.worldTransform = transform;
    return light;
}

// Three prims of 12 strands, lit by `light` alone.
Scene tuftUnder(const LightPrim& light) {
    Scene scene;
    scene.setCurves(testscenes::tuftStrands("/tuft/a", 1, 12, 0.0f));
    scene.setCurves(testscenes::tuftStrands("/tuft/b", 2, 12, 1.0f));
    scene.setCurves(testscenes::tuftStrands("/tuft/c", 3, 12, 2.0f));
    scene.setLight(light);
    return scene;
}

constexpr int kImageWidth = 64;

// The reference's lights, and the maps they cast: 512 maps of 128² texels
// take 128 MB. Both paths render at this map resolution, so the shadow
// comparison measures the scheme, not the resolution.
const char* const kSampledLights = "512";
const char* const kMapResolution = "128";

RenderResult render(const Scene& scene, RenderSettings settings) {
    Renderer renderer(gl::GlBackend::Egl);
    Diagnostics diagnostics;
    settings.set("lightsPerPass", "16");
    settings.set("shadowMapResolution", kMapResolution);
    RenderResult result = renderer.render(scene, testscenes::tuftCamera(0.0, kImageWidth), settings, diagnostics);
    EXPECT_EQ(diagnostics.warningCount(), 0u);
    return result;
}

RenderSettings withSettings(std::initializer_list<std::pair<const char*, const char*>> assignments) {
    RenderSettings settings;
    for (const auto& [name, value] : assignments) settings.set(name, value);
    return settings;
}

RenderResult reference(const Scene& scene, bool shadows) {
    return render(scene, withSettings({{"domeLighting", "sampled"},
                                       {"domeSampledLights", kSampledLights},
                                       {"shadowMode", shadows ? "deepOpacity" : "off"}}));
}

RelativeColorError errorOf(const RenderResult& actual, const RenderResult& expected, const char* what) {
    const RelativeColorError error = relativeColorError(actual.color, expected.color);
    std::cout << what << ": relative RMSE " << error.rootMeanSquare << ", largest " << error.largest
              << ", sum ratio " << error.sumRatio << " over "
              << error.coveredPixels << " pixels\n";
    EXPECT_GT(error.coveredPixels, 300u) << what;
    return error;
}

}  // namespace

TEST_F(DomeReference, TheReferenceIsExplainedAndSampledLikeAnyDistantLights) {
    const RenderResult result = reference(tuftUnder(dome(writeSky(path("sky.exr")))), true);
    const RenderPlan& plan = result.plan;
    ASSERT_EQ(plan.recipe().lighting.domes.size(), 1u);
    EXPECT_EQ(plan.recipe().lighting.domes[0].sampledLights, 512u);
    EXPECT_EQ(plan.recipe().lighting.domes[0].shadowedLights, 512u);
    EXPECT_EQ(plan.recipe().lighting.domes[0].srbfLights, 0u);
    ASSERT_EQ(plan.recipe().lighting.lights.lights.size(), 512u);
    EXPECT_FALSE(plan.recipe().lighting.lights.lights[0].isSrbf());
    EXPECT_EQ(plan.recipe().shadows.lights.size(), 512u);
    EXPECT_TRUE(plan.recipe().shadows.sharedMaps.empty());
    EXPECT_EQ(plan.recipe().lighting.batches.size(), 32u);
    EXPECT_NE(plan.describe().find("the reference (domeLighting=sampled): 512 distant lights importance-sampled"),
              std::string::npos)
        << plan.describe();
}

TEST_F(DomeReference, AUniformDomesAnalyticTermIsWithinOnePercentOfItsReference) {
    LightPrim uniform = dome("");
    uniform.color = glm::vec3(0.5f, 0.6f, 0.7f);
    const Scene scene = tuftUnder(uniform);
    const RenderResult analytic = render(scene, withSettings({{"shadowMode", "off"}}));
    const RenderResult sampled = reference(scene, false);
    const RelativeColorError error = errorOf(analytic, sampled, "uniform dome, analytic");
    EXPECT_LT(error.rootMeanSquare, 0.01);
    EXPECT_LT(error.largest, 0.03);

    // Mutation: the dome 5 % brighter on one side is out of the bound.
    uniform.intensity *= 1.05f;
    const RelativeColorError brighter = errorOf(render(tuftUnder(uniform), withSettings({{"shadowMode", "off"}})),
                                                sampled, "uniform dome 5 % brighter");
    EXPECT_GT(brighter.rootMeanSquare, 0.03);
}

TEST_F(DomeReference, UnshadowedSrbfLightingIsWithinItsBoundOfTheReference) {
    const std::string sky = writeSky(path("sky.exr"));
    const Scene scene = tuftUnder(dome(sky));
    const RenderResult sampled = reference(scene, false);
    const RenderResult srbf = render(scene, withSettings({{"shadowMode", "off"}}));
    const RelativeColorError error = errorOf(srbf, sampled, "30 SRBFs, unshadowed");
    // Measured 0.015 and 0.021 (the fit keeps the map's power, SrbfFit.h;
    // without that, 0.12: a tenth too dim).
    EXPECT_LT(error.rootMeanSquare, 0.04);
    EXPECT_LT(error.largest, 0.06);

    // Mutations the bound must catch: the lobes a quarter too bright (0.26),
    // and the dome turned 90° about +Y, the sun on the tuft's other side (0.06).
    LightPrim brighter = dome(sky);
    brighter.intensity *= 1.25f;
    EXPECT_GT(errorOf(render(tuftUnder(brighter), withSettings({{"shadowMode", "off"}})), sampled,
                      "lobes 25 % brighter")
                  .rootMeanSquare,
              0.04);
    const Scene turned = tuftUnder(dome(sky, glm::rotate(glm::dmat4(1.0), glm::radians(90.0), glm::dvec3(0, 1, 0))));
    EXPECT_GT(errorOf(render(turned, withSettings({{"shadowMode", "off"}})), sampled, "dome turned 90°").rootMeanSquare,
              0.04);
}

TEST_F(DomeReference, ShadowedSrbfLightingIsWithinItsBoundOfTheReference) {
    const Scene scene = tuftUnder(dome(writeSky(path("sky.exr"))));
    const RenderResult sampled = reference(scene, true);
    // The default: the paper's convolution optical depth map
    // (domeShadowFilter=mipmap), the layers averaged from a mip chain in a
    // pass of its own.
    const RenderResult shadowed = render(scene, RenderSettings{});
    EXPECT_TRUE(shadowed.plan.isEnabled("opacityMipmaps"));
    const RelativeColorError error = errorOf(shadowed, sampled, "30 SRBFs, 4 maps, mip chain");
    // Measured 0.081 and 0.084, 8 % too bright overall: the 26 lobes that
    // borrow a map see it through the nearest of 4 directions, and hair
    // shadows less across a lobe's width than along its centre.
    EXPECT_LT(error.rootMeanSquare, 0.12);
    EXPECT_LT(error.largest, 0.15);

    // Nine taps of transmittance instead (0.083 and 0.086 here).
    const RenderResult taps = render(scene, withSettings({{"domeShadowFilter", "taps"}}));
    EXPECT_FALSE(taps.plan.isEnabled("opacityMipmaps"));
    EXPECT_NE(taps.color.pixels, shadowed.color.pixels);
    const RelativeColorError tapsError = errorOf(taps, sampled, "30 SRBFs, 4 maps, taps");
    EXPECT_LT(tapsError.rootMeanSquare, 0.12);
    EXPECT_LT(tapsError.largest, 0.15);

    // Mutation: the SRBF path without its shadows is further off (0.126).
    const RelativeColorError unshadowed =
        errorOf(render(scene, withSettings({{"shadowMode", "off"}})), sampled, "30 SRBFs, shadows off");
    EXPECT_GT(unshadowed.rootMeanSquare, 1.3 * error.rootMeanSquare);
}

TEST_F(DomeReference, AReferenceWhoseMapsDoNotFitFailsRatherThanDrawLightsUnshadowed) {
    const Scene scene = tuftUnder(dome(""));
    RenderSettings settings = withSettings({{"domeLighting", "sampled"}, {"domeSampledLights", "1024"}});
    settings.set("shadowMapResolution", "1024");  // 16 MB a map: 64 of them fill the default 1024 MB
    Renderer renderer(gl::GlBackend::Egl);
    Diagnostics diagnostics;
    try {
        renderer.render(scene, testscenes::tuftCamera(0.0, 16), settings, diagnostics);
        FAIL() << "a reference with lights left unshadowed was drawn";
    } catch (const std::invalid_argument& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("domeLighting=sampled: 1024 lights cast shadows, more than the 64 maps"),
                  std::string::npos)
            << message;
    }
}
