// Dome lighting on the GPU (hdHair/plan/DomeLighting.h): the shader's
// SRBF-table lookup against sampleSrbfTable on the CPU, turning the dome,
// the uniform dome's analytic term, domeLighting=ambient's old flat term, a
// missing texture, the plan's shadows and --explain, the shadows drawn, and
// mutations the pixel comparison must catch.

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/environment/DomeEnvironment.h"
#include "hdHair/environment/tests/LatlongTestTextures.h"
#include "hdHair/curves/PreparedCurves.h"
#include "hdHair/plan/HairMaterial.h"
#include "hdHair/render/Renderer.h"
#include "hdHair/meshes/tests/TestMeshes.h"
#include "hdHair/render/tests/OwnCacheFolderTest.h"
#include "hdHair/render/tests/SquareCamera.h"
#include "hdHair/scene/tests/AuthoredPrimvar.h"
#include "hdHair/scene/Scene.h"
#include "hdHair/shading/SrbfTableCache.h"
#include "hdHair/shading/SrbfUniformDome.h"
#include "hdHair/shading/SrbfVaryingAbsorption.h"

using namespace hdhair;
using hdhair::test::squareCamera;

namespace {

const glm::vec3 kHairColor(0.6f, 0.4f, 0.3f);
const KajiyaKayParameters kKajiyaKay;  // the settings' defaults: Kd 1, Ks 0.35, p 60

// The SRBF tables go to a folder of the test's own.
class DomeLighting : public test::OwnCacheFolderTest {};

CurvesPrim strand(const std::string& path, glm::vec3 from, glm::vec3 to) {
    CurvesPrim prim;
    prim.path = path;
    prim.type = CurveType::Linear;
    prim.curveVertexCounts = {2};
    prim.points = {from, to};
    prim.primvars["widths"].name = "widths";
    prim.primvars["widths"].values = {0.2f};
    Primvar color;
    color.name = "displayColor";
    color.tupleSize = 3;
    color.values = {kHairColor.r, kHairColor.g, kHairColor.b};
    prim.primvars["displayColor"] = color;
    return prim;
}

// A horizontal strand (tangent +X) at y = 0.5 and a vertical one (+Y) at
// x = 0.5 below it, both in the plane z = 0.
Scene twoStrands() {
    Scene scene;
    scene.setCurves(strand("/horizontal", {-1.0f, 0.5f, 0.0f}, {1.0f, 0.5f, 0.0f}));
    scene.setCurves(strand("/vertical", {0.5f, -1.0f, 0.0f}, {0.5f, 0.2f, 0.0f}));
    return scene;
}

LightPrim dome(const std::string& textureFile, glm::dmat4 transform = glm::dmat4(1.0)) {
    LightPrim light;
    light.path = "/World/dome";
    light.type = LightType::Dome;
    light.textureFile = textureFile;
    light.worldTransform = transform;
    return light;
}

// A dim sky over dark ground with a sun towards +Z, slightly up, in the
// dome's frame, that gives most of the light (test::proceduralSky's sun,
// under a sky a sixth as bright).
const glm::vec3 kSun = glm::normalize(glm::vec3(0.0f, 0.3f, 1.0f));

glm::vec3 sunnySky(const glm::vec3& d) {
    const glm::vec3 sky = d.y >= 0.0f ? glm::vec3(0.05f, 0.08f, 0.15f) * (0.4f + 0.6f * d.y)
                                      : glm::vec3(0.02f, 0.015f, 0.01f);
    return sky + glm::vec3(40.0f, 36.0f, 30.0f) * std::exp(300.0f * (glm::dot(d, kSun) - 1.0f));
}

std::string writeSky(const std::string& file) {
    const int width = 128, height = 64;
    test::writeTestImage(file, width, height, 3, test::latlongPixels(width, height, sunnySky));
    return file;
}

// The colour of the covered (alpha 1) pixels of row `y` between x = ±0.8.
struct RowPixels {
    std::vector<glm::vec3> colors;
};
RowPixels coveredRow(const RenderResult& result, const CameraView& camera, float y) {
    RowPixels row;
    const int py = int(camera.worldToPixel(glm::dvec3(0.0, y, 0.0)).y);
    const int x0 = int(camera.worldToPixel(glm::dvec3(-0.8, y, 0.0)).x);
    const int x1 = int(camera.worldToPixel(glm::dvec3(0.8, y, 0.0)).x);
    for (int x = x0; x <= x1; ++x)
        if (result.color.at(x, py, 3) == 1.0f)
            row.colors.emplace_back(result.color.at(x, py, 0), result.color.at(x, py, 1), result.color.at(x, py, 2));
    return row;
}

glm::vec3 pixelAt(const RenderResult& result, const CameraView& camera, glm::vec2 world) {
    const glm::dvec3 p = camera.worldToPixel(glm::dvec3(world, 0.0));
    const int x = int(p.x), y = int(p.y);
    return {result.color.at(x, y, 0), result.color.at(x, y, 1), result.color.at(x, y, 2)};
}

// The largest difference of any covered pixel from `expected`, relative to it.
float largestRelativeDifference(const RowPixels& row, const glm::vec3& expected) {
    float largest = 0.0f;
    for (const glm::vec3& color : row.colors)
        for (int c = 0; c < 3; ++c) largest = std::max(largest, std::abs(color[c] - expected[c]) / expected[c]);
    return largest;
}

// What a Kajiya-Kay strand of tangent t seen along ωo reflects under the
// lobes, from the table on the CPU (Ren eq. 4 with T̃ = 1).
glm::vec3 expectedKajiyaKay(const std::vector<Srbf>& srbfs, const SrbfConvolutionTable& table, glm::vec3 t,
                            glm::vec3 wo, size_t skip = size_t(-1)) {
    glm::vec3 sum(0.0f);
    for (size_t j = 0; j < srbfs.size(); ++j) {
        if (j == skip) continue;
        KajiyaKayTerms terms = evaluateSrbfKajiyaKayTable(table, t, wo, srbfs[j].lobe, kKajiyaKay);
        sum += srbfs[j].amplitude * (terms.diffuse * kHairColor + terms.specular);
    }
    return sum;
}

// The frame of `scene` without shadows (T̃ = 1: the tables alone), with no warning.
// Single scattering, unshadowed: what the SRBF tables hold (multiple
// scattering under a dome: testMultipleScattering).
RenderResult renderUnshadowed(const Scene& scene, RenderSettings settings, const CameraView& camera) {
    settings.set("shadowMode", "off");
    settings.set("multipleScattering", "off");
    Renderer renderer(gl::GlBackend::Egl);
    Diagnostics diagnostics;
    RenderResult result = renderer.render(scene, camera, settings, diagnostics);
    EXPECT_EQ(diagnostics.warningCount(), 0u);
    return result;
}

}  // namespace

TEST_F(DomeLighting, TheShaderLooksUpTheTablesAsTheCpuDoes) {
    const std::string sky = writeSky(path("sky.exr"));
    Scene scene = twoStrands();
    scene.setLight(dome(sky));
    const CameraView camera = squareCamera(96);
    RenderResult result = renderUnshadowed(scene, RenderSettings{}, camera);

    // The lobes the renderer drew (the same fit, from the process's cache)
    // and the table it read.
    Diagnostics cpu;
    DomeEnvironment environment = domeEnvironment(dome(sky), glm::vec3(1.0f), DomeFitSettings(), cpu);
    ASSERT_EQ(environment.srbfs.size(), 30u);
    SrbfTableCache cache("");
    const SrbfConvolutionTable& table = *cache.table(srbfKajiyaKayTableRequest(kKajiyaKay.shininess), cpu);
    const glm::vec3 t(1.0f, 0.0f, 0.0f), wo(0.0f, 0.0f, 1.0f);
    const glm::vec3 expected = expectedKajiyaKay(environment.srbfs, table, t, wo);

    const RowPixels row = coveredRow(result, camera, 0.5f);
    ASSERT_GT(row.colors.size(), 50u);
    const float tolerance = 0.01f;  // GL's 8-bit texel weights and float sums
    const float difference = largestRelativeDifference(row, expected);
    std::cout << row.colors.size() << " covered pixels, largest difference from the CPU lookup "
              << 100.0f * difference << " %\n";
    EXPECT_LT(difference, tolerance) << "expected " << expected.r << " " << expected.g << " " << expected.b;

    // Mutations the comparison must catch: the lobe that adds most here
    // left out, and the table 5 % too bright.
    size_t strongest = 0;
    float most = 0.0f;
    for (size_t j = 0; j < environment.srbfs.size(); ++j) {
        const float added = glm::length(expected - expectedKajiyaKay(environment.srbfs, table, t, wo, j));
        if (added > most) most = added, strongest = j;
    }
    EXPECT_GT(largestRelativeDifference(row, expectedKajiyaKay(environment.srbfs, table, t, wo, strongest)),
              tolerance);
    EXPECT_GT(largestRelativeDifference(row, expected * 1.05f), tolerance);
}

TEST_F(DomeLighting, MarschnerStrandsReadTheirMaterialsRgbTable) {
    // As above for Marschner: the RGB table of the prim's own fibre
    // parameters (absorption from its displayColor), 32 azimuths wide.
    const std::string sky = writeSky(path("sky.exr"));
    Scene scene = twoStrands();
    scene.setLight(dome(sky));
    RenderSettings settings;
    settings.set("shadingModel", "marschner");
    const CameraView camera = squareCamera(96);
    RenderResult result = renderUnshadowed(scene, settings, camera);
    Diagnostics diagnostics;

    const CurvesPrim& prim = *scene.curves().at("/horizontal").prim;
    const HairMaterial material =
        hairMaterialFor(prim, prepareCurves(prim, diagnostics, hairParameterPrimvars()), settings, diagnostics);
    ASSERT_EQ(material.model, ShadingModel::Marschner);
    DomeEnvironment environment = domeEnvironment(dome(sky), glm::vec3(1.0f), DomeFitSettings(), diagnostics);
    SrbfTableCache cache(path("cache"));  // the file the renderer wrote
    const SrbfConvolutionTable& table = *cache.table(srbfMarschnerTableRequest(material.marschner), diagnostics);
    EXPECT_EQ(cache.counts().builds, 0);
    const glm::vec3 t(1.0f, 0.0f, 0.0f), wo(0.0f, 0.0f, 1.0f);
    auto expectedMarschner = [&](size_t skip) {
        glm::vec3 sum(0.0f);
        for (size_t j = 0; j < environment.srbfs.size(); ++j)
            if (j != skip)
                sum += environment.srbfs[j].amplitude * evaluateSrbfMarschnerTable(table, t, wo, environment.srbfs[j].lobe);
        return sum;
    };
    const glm::vec3 expected = expectedMarschner(size_t(-1));
    const RowPixels row = coveredRow(result, camera, 0.5f);
    ASSERT_GT(row.colors.size(), 50u);
    const float difference = largestRelativeDifference(row, expected);
    std::cout << "Marschner: largest difference from the CPU lookup " << 100.0f * difference << " %\n";
    EXPECT_LT(difference, 0.01f);
    EXPECT_GT(largestRelativeDifference(row, expected * 1.05f), 0.01f);
    EXPECT_GT(largestRelativeDifference(row, expectedMarschner(0)), 0.01f);  // the strongest lobe left out
}

TEST_F(DomeLighting, AbsorptionThatVariesPerCurveIsPutBackPerFragment) {
    // Two curves of one prim, blonde and dark (hdHair:absorption per curve):
    // no RGB table fits both, so the prim reads the lobes apart at σ_a = 0
    // and each fragment weighs TT and TRT by its own absorption
    // (SrbfVaryingAbsorption.h), which the CPU does the same way.
    const std::string sky = writeSky(path("sky.exr"));
    CurvesPrim prim;
    prim.path = "/hair";
    prim.type = CurveType::Linear;
    prim.curveVertexCounts = {2, 2};
    prim.points = {{-1.0f, 0.5f, 0.0f}, {1.0f, 0.5f, 0.0f}, {-1.0f, -0.5f, 0.0f}, {1.0f, -0.5f, 0.0f}};
    prim.shadingModel = "marschner";
    prim.primvars["widths"].name = "widths";
    prim.primvars["widths"].values = {0.2f};
    const glm::vec3 blonde(0.015f, 0.035f, 0.075f), dark(0.6f, 0.9f, 1.4f);
    prim.primvars["hdHair:absorption"] = test::authoredPrimvar(
        "hdHair:absorption", Interpolation::Uniform, 3, {blonde.r, blonde.g, blonde.b, dark.r, dark.g, dark.b});
    Scene scene;
    scene.setCurves(prim);
    scene.setLight(dome(sky));
    const CameraView camera = squareCamera(96);
    const RenderSettings settings;
    RenderResult result = renderUnshadowed(scene, settings, camera);
    Diagnostics diagnostics;

    const HairMaterial material =
        hairMaterialFor(prim, prepareCurves(prim, diagnostics, hairParameterPrimvars()), settings, diagnostics);
    ASSERT_TRUE(material.varies & kAbsorptionVaries);
    DomeEnvironment environment = domeEnvironment(dome(sky), glm::vec3(1.0f), DomeFitSettings(), diagnostics);
    SrbfTableCache cache(path("cache"));
    const SrbfConvolutionTable& lobes = *cache.table(srbfMarschnerLobeTableRequest(material.marschner), diagnostics);
    EXPECT_EQ(cache.counts().builds, 0);  // the renderer built and wrote this table
    const glm::vec3 t(1.0f, 0.0f, 0.0f), wo(0.0f, 0.0f, 1.0f);
    for (auto [y, sigmaA] : {std::pair{0.5f, blonde}, std::pair{-0.5f, dark}}) {
        glm::vec3 expected(0.0f);
        for (const Srbf& srbf : environment.srbfs)
            expected += srbf.amplitude *
                        evaluateSrbfMarschnerVaryingAbsorption(lobes, t, wo, srbf.lobe, sigmaA, material.marschner);
        const RowPixels row = coveredRow(result, camera, y);
        ASSERT_GT(row.colors.size(), 50u);
        const float difference = largestRelativeDifference(row, expected);
        std::cout << "absorption per curve, y = " << y << ": largest difference from the CPU " << 100.0f * difference
                  << " %\n";
        EXPECT_LT(difference, 0.01f) << y;
        EXPECT_GT(largestRelativeDifference(row, expected * 1.05f), 0.01f) << y;
    }
}

TEST_F(DomeLighting, TurningTheDomeMovesTheLitSide) {
    // The sun from +Z (towards the camera) lights both strands; turned 90°
    // about +Y it comes from +X, along the horizontal strand, which then
    // loses its diffuse light while the vertical one keeps it.
    const std::string sky = writeSky(path("sky.exr"));
    Renderer renderer(gl::GlBackend::Egl);
    const CameraView camera = squareCamera(96);
    RenderSettings settings;
    settings.set("shadowMode", "off");
    auto render = [&](glm::dmat4 transform) {
        Scene scene = twoStrands();
        scene.setLight(dome(sky, transform));
        Diagnostics diagnostics;
        return renderer.render(scene, camera, settings, diagnostics);
    };
    const RenderResult still = render(glm::dmat4(1.0));
    const RenderResult turned = render(glm::rotate(glm::dmat4(1.0), glm::radians(90.0), glm::dvec3(0.0, 1.0, 0.0)));
    const float horizontalStill = pixelAt(still, camera, {-0.5f, 0.5f}).r;
    const float horizontalTurned = pixelAt(turned, camera, {-0.5f, 0.5f}).r;
    const float verticalStill = pixelAt(still, camera, {0.5f, -0.5f}).r;
    const float verticalTurned = pixelAt(turned, camera, {0.5f, -0.5f}).r;
    EXPECT_LT(horizontalTurned, 0.6f * horizontalStill);
    EXPECT_GT(verticalTurned, 0.8f * verticalStill);
}

// Unshadowed (the dome's inputs:shadow:enable off), a uniform dome gives
// the model's exact response. Shadowed (the default), it reaches the
// strands through the density volume: the same far from the other strand
// (the row's left third), darker above the vertical strand's top, which
// hides part of the sky below (docs/how-it-works.md, "Hair density volume").
TEST_F(DomeLighting, AUniformDomeIsTheModelsExactResponse) {
    Scene scene = twoStrands();
    LightPrim uniform = dome("");
    uniform.color = glm::vec3(0.5f, 0.6f, 0.7f);
    uniform.shadowEnable = false;
    scene.setLight(uniform);
    Renderer renderer(gl::GlBackend::Egl);
    const CameraView camera = squareCamera(96);
    Diagnostics diagnostics;
    RenderSettings settings;
    RenderResult srbf = renderer.render(scene, camera, settings, diagnostics);
    EXPECT_NE(srbf.plan.describe().find("dome /World/dome: uniform dome: analytic"), std::string::npos);
    // L (Kd·colour·U_d(θ_o) + Ks·U_s(θ_o)), U_d = π (SrbfUniformDome.h; its
    // test checks U against the model integrated over the sphere).
    SrbfTableCache cache("");
    const std::vector<glm::vec3> response =
        srbfUniformDomeResponse(*cache.table(srbfKajiyaKayTableRequest(kKajiyaKay.shininess), diagnostics));
    const glm::vec3 u = sampleSrbfUniformDome(response, 0.0f);
    const glm::vec3 expected = uniform.color * (kKajiyaKay.diffuse * u.x * kHairColor + kKajiyaKay.specular * u.y);
    EXPECT_LT(largestRelativeDifference(coveredRow(srbf, camera, 0.5f), expected), 1e-3f);
    EXPECT_GT(largestRelativeDifference(coveredRow(srbf, camera, 0.5f), expected * 1.05f), 1e-3f);

    Scene shadowedScene = twoStrands();
    uniform.shadowEnable = true;
    shadowedScene.setLight(uniform);
    const RenderResult shadowed = renderer.render(shadowedScene, camera, settings, diagnostics);
    EXPECT_TRUE(shadowed.plan.isEnabled("densityVolume"));
    RowPixels far = coveredRow(shadowed, camera, 0.5f);
    far.colors.resize(far.colors.size() / 3);
    EXPECT_LT(largestRelativeDifference(far, expected), 1e-3f);
    EXPECT_LT(pixelAt(shadowed, camera, {0.5f, 0.5f}).g, 0.95f * expected.g);

    // domeLighting=ambient: the old flat term, radiance × colour, exactly.
    settings.set("domeLighting", "ambient");
    RenderResult ambient = renderer.render(scene, camera, settings, diagnostics);
    EXPECT_EQ(largestRelativeDifference(coveredRow(ambient, camera, 0.5f), uniform.color * kHairColor), 0.0f);
    EXPECT_EQ(diagnostics.warningCount(), 0u);
}

TEST_F(DomeLighting, AMissingTextureWarnsAndLightsUniformly) {
    Renderer renderer(gl::GlBackend::Egl);
    const CameraView camera = squareCamera(64);
    auto render = [&](const std::string& file, Diagnostics& diagnostics) {
        Scene scene = twoStrands();
        scene.setLight(dome(file));
        return renderer.render(scene, camera, RenderSettings{}, diagnostics);
    };
    Diagnostics missing, untextured;
    const std::string file = path("no such sky.exr");
    RenderResult withMissing = render(file, missing);
    RenderResult uniform = render("", untextured);
    ASSERT_EQ(missing.warningCount(), 1u);
    const std::string warning = missing.warnings().front().where + ": " + missing.warnings().front().message;
    EXPECT_NE(warning.find("/World/dome"), std::string::npos) << warning;
    EXPECT_NE(warning.find(file), std::string::npos) << warning;
    EXPECT_EQ(untextured.warningCount(), 0u);
    EXPECT_EQ(withMissing.color.pixels, uniform.color.pixels);
}

TEST_F(DomeLighting, ThePlanShadowsTheStrongestLobesAndExplainsTheDome) {
    const std::string sky = writeSky(path("sky.exr"));
    Scene scene = twoStrands();
    scene.setLight(dome(sky));
    Renderer renderer(gl::GlBackend::Egl);
    Diagnostics diagnostics;
    RenderSettings settings;
    settings.set("domeLights", "12");
    settings.set("domeShadowLights", "3");
    RenderResult result = renderer.render(scene, squareCamera(48), settings, diagnostics);
    const RenderPlan& plan = result.plan;
    ASSERT_EQ(plan.recipe().lighting.domes.size(), 1u);
    EXPECT_EQ(plan.recipe().lighting.domes[0].srbfLights, 12u);
    EXPECT_EQ(plan.recipe().lighting.domes[0].shadowedLights, 3u);
    ASSERT_EQ(plan.recipe().lighting.lights.lights.size(), 12u);  // no camera light: the dome lights the stage
    EXPECT_EQ(plan.recipe().shadows.lights.size(), 3u);
    EXPECT_EQ(plan.recipe().shadows.sharedMaps.size(), 9u);
    for (size_t light = 0; light < 12; ++light) EXPECT_GE(plan.recipe().shadows.shadowOf(light), 0) << light;
    EXPECT_TRUE(plan.isEnabled("deepOpacity /World/dome srbf 0"));
    EXPECT_NE(plan.describe().find("dome /World/dome: 12 SRBF lights (fit error"), std::string::npos)
        << plan.describe();
    EXPECT_NE(plan.describe().find("4 per pass"), std::string::npos);
    EXPECT_EQ(plan.recipe().lighting.batches.size(), 3u);
}

TEST_F(DomeLighting, TheStrongestLobesShadowTheHairBehind) {
    // The dome turned -90° about +X brings the sun from above (+Y, a little
    // from -Z): the strand at y = 0 lies in the shadow of the one at y = 0.3,
    // z = -0.09, which nothing shadows. The camera sees both side by side.
    const std::string sky = writeSky(path("sky.exr"));
    Scene scene;
    scene.setCurves(strand("/lower", {-1.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}));
    scene.setCurves(strand("/upper", {-1.0f, 0.3f, -0.09f}, {1.0f, 0.3f, -0.09f}));
    scene.setLight(dome(sky, glm::rotate(glm::dmat4(1.0), glm::radians(-90.0), glm::dvec3(1.0, 0.0, 0.0))));
    Renderer renderer(gl::GlBackend::Egl);
    const CameraView camera = squareCamera(96);
    auto render = [&](const char* setting, const char* value) {
        RenderSettings settings;
        settings.set(setting, value);
        Diagnostics diagnostics;
        RenderResult result = renderer.render(scene, camera, settings, diagnostics);
        EXPECT_EQ(diagnostics.warningCount(), 0u);
        return result;
    };
    const RenderResult shadowed = render("domeShadowLights", "4");
    const RenderResult unshadowed = render("shadowMode", "off");
    const glm::vec3 lower = pixelAt(shadowed, camera, {-0.5f, 0.0f}), lowerLit = pixelAt(unshadowed, camera, {-0.5f, 0.0f});
    const glm::vec3 upper = pixelAt(shadowed, camera, {-0.5f, 0.3f}), upperLit = pixelAt(unshadowed, camera, {-0.5f, 0.3f});
    std::cout << "shadowed / unshadowed red: lower strand " << lower.r / lowerLit.r << ", upper "
              << upper.r / upperLit.r << "\n";
    EXPECT_LT(lower.r, 0.6f * lowerLit.r);
    EXPECT_GT(upper.r, 0.85f * upperLit.r);
    // No maps at all: what shadowMode=off gives, pixel for pixel.
    EXPECT_EQ(render("domeShadowLights", "0").color.pixels, unshadowed.color.pixels);
}

TEST_F(DomeLighting, AMeshUnderADomeWithNoCurvesPlansNoMipChain) {
    // No strands: no lobe gets a map, so no batch reads the mip chain and
    // no pass makes it (a batch that read it would fail the frame graph).
    Scene scene;
    scene.setMesh(test::uvSphere("/sphere", glm::vec3(0.0f), 0.8f));
    scene.setLight(dome(writeSky(path("sky.exr"))));
    Renderer renderer(gl::GlBackend::Egl);
    Diagnostics diagnostics;
    RenderSettings settings;
    settings.set("lightsPerPass", "4");
    const RenderResult result = renderer.render(scene, squareCamera(32), settings, diagnostics);
    EXPECT_FALSE(result.plan.isEnabled("opacityMipmaps"));
    EXPECT_TRUE(result.plan.isEnabled("lightBatch 2"));
    EXPECT_GT(pixelAt(result, squareCamera(32), {0.0f, 0.0f}).r, 0.0f);
}
