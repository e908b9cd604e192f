// The GPU shades as the CPU models say: a single straight strand under one
// distant light, seen by an orthographic camera, so the tangent, the eye and
// the light direction at its centre pixel are known exactly. And hair
// parameters chosen per prim through HdHairAPI primvars.

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "DistantLight.h"
#include "OrthographicView.h"
#include "StageRendering.h"
#include "hdHair/plan/CameraView.h"
#include "hdHair/plan/HairMaterial.h"
#include "hdHair/scene/Scene.h"
#include "hdHair/scene/tests/AuthoredPrimvar.h"
#include "hdHair/shading/KajiyaKay.h"
#include "hdHair/shading/Marschner.h"
#include "hdHair/shading/MarschnerTables.h"
#include "hdHair/shading/ShadingLight.h"

using namespace hdhair;
using hdhair::test::authoredPrimvar;
using namespace hdhair::testenv;

namespace {

Primvar constant(const std::string& name, std::vector<float> values) {
    Primvar primvar;
    primvar.name = name;
    primvar.tupleSize = int(values.size());
    primvar.values = std::move(values);
    return primvar;
}

// A strand along +X through the origin, 0.5 wide (many pixels: opaque path).
CurvesPrim strand(const std::string& path, float y, glm::vec3 color) {
    CurvesPrim prim;
    prim.path = path;
    prim.type = CurveType::Linear;
    prim.curveVertexCounts = {2};
    prim.points = {{-2.0f, y, 0.0f}, {2.0f, y, 0.0f}};
    prim.primvars["widths"] = constant("widths", {0.5f});
    prim.primvars["displayColor"] = constant("displayColor", {color.r, color.g, color.b});
    return prim;
}

CameraView camera() { return orthographicView(2.4, 64); }

// A distant light shining from `towardsLight`.
LightPrim distantFrom(glm::dvec3 towardsLight) { return distantLightFrom(towardsLight); }

// Single scattering: what the CPU models here compute (multiple scattering
// has its own tests, testMultipleScattering).
RenderSettings withModel(const std::string& model, const std::string& azimuthal = "auto") {
    RenderSettings settings;
    settings.set("shadingModel", model);
    settings.set("marschner:azimuthal", azimuthal);
    settings.set("multipleScattering", "off");
    return settings;
}

glm::vec3 pixel(const RenderResult& result, int x, int y) {
    return glm::vec3(result.color.at(x, y, 0), result.color.at(x, y, 1), result.color.at(x, y, 2));
}

RenderResult renderScene(const Scene& scene, const RenderSettings& settings) {
    Diagnostics diagnostics;
    RenderResult result = sharedRenderer().render(scene, camera(), settings, diagnostics);
    EXPECT_TRUE(diagnostics.warnings().empty());
    return result;
}

glm::vec3 centrePixel(const Scene& scene, const RenderSettings& settings) {
    RenderResult result = renderScene(scene, settings);
    EXPECT_EQ(result.stats.transparency, "opaque");
    return pixel(result, 32, 32);
}

glm::vec3 centrePixel(const Scene& scene, const std::string& model) { return centrePixel(scene, withModel(model)); }

const glm::dvec3 kLightDirections[] = {
    {0.0, 0.6, 1.0},    // in front, above
    {1.0, 0.2, 0.3},    // along the fibre, grazing
    {-0.5, -0.8, 0.2},  // from below, behind the strand's side
    {0.3, 0.1, -1.0},   // behind the strand: transmission
};

}  // namespace

TEST(ShadingModels, GpuKajiyaKayMatchesTheCpuModel) {
    const glm::vec3 color(0.6f, 0.4f, 0.2f);
    for (const glm::dvec3& direction : kLightDirections) {
        Scene scene;
        scene.setCurves(strand("/hair", 0.0f, color));
        scene.setLight(distantFrom(direction));
        glm::vec3 gpu = centrePixel(scene, "kajiyaKay");
        KajiyaKayTerms terms = evaluateKajiyaKay({1, 0, 0}, glm::vec3(glm::normalize(direction)), {0, 0, 1},
                                                 KajiyaKayParameters{});
        glm::vec3 cpu = 2.0f * (terms.diffuse * color + terms.specular);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(gpu[c], cpu[c], 1e-4f + 1e-3f * cpu[c]) << c;
    }
}

// The centre pixel of a brown strand lit from `direction`, and the material
// the renderer resolved for it.
struct LitStrand {
    glm::vec3 gpu;
    HairMaterial material;
};
LitStrand renderLitStrand(const glm::dvec3& direction, const RenderSettings& settings) {
    Scene scene;
    CurvesPrim hair = strand("/hair", 0.0f, {0.5f, 0.3f, 0.15f});
    scene.setCurves(hair);
    scene.setLight(distantFrom(direction));
    Diagnostics diagnostics;
    return {centrePixel(scene, settings),
            hairMaterialFor(hair, prepareCurves(hair, diagnostics, hairParameterPrimvars()), settings, diagnostics)};
}

TEST(ShadingModels, GpuMarschnerMatchesTheCpuTabledModel) {
    for (const glm::dvec3& direction : kLightDirections) {
        auto [gpu, material] = renderLitStrand(direction, withModel("marschner"));
        MarschnerTables tables = buildMarschnerTables(material.marschner);
        MarschnerLobes lobes = evaluateMarschnerTabled({1, 0, 0}, glm::vec3(glm::normalize(direction)), {0, 0, 1},
                                                       material.marschner, tables);
        glm::vec3 cpu = 2.0f * lobes.radiance();
        // Half-float tables are the same texels on both sides; the GPU's
        // bilinear weights carry 8 bits of fraction (GL's minimum).
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(gpu[c], cpu[c], 2e-3f + 0.02f * cpu[c]) << c << " light " << direction.x;
    }
}

TEST(ShadingModels, GpuAnalyticMarschnerMatchesTheCpuModel) {
    for (const glm::dvec3& direction : kLightDirections) {
        auto [gpu, material] = renderLitStrand(direction, withModel("marschner", "analytic"));
        ASSERT_TRUE(material.analyticAzimuthal);
        MarschnerLobes lobes = evaluateMarschner({1, 0, 0}, glm::vec3(glm::normalize(direction)), {0, 0, 1},
                                                 material.marschner);
        glm::vec3 cpu = 2.0f * lobes.radiance();
        // Single against double precision, the same formulas.
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(gpu[c], cpu[c], 1e-4f + 2e-3f * cpu[c]) << c << " light " << direction.x;
    }
}

TEST(ShadingModels, GpuAnalyticMarschnerStaysFiniteAtHardAngles) {
    const glm::dvec3 directions[] = {{1.0, 0.0, 0.0}, {0.0, 0.0, -1.0}, {0.0, 0.0, 1.0}, {0.0, 1.0, 0.0}};
    // The ends of the documented ranges (values beyond them are clamped to
    // them with a warning: ParametersOutsideTheirRangeAreClampedWithAWarning).
    const std::vector<std::pair<std::string, std::vector<float>>> fibres = {
        {"hdHair:eta", {1.001f}}, {"hdHair:eta", {2.0f}}, {"hdHair:absorption", {0.0f, 0.0f, 0.0f}},
        {"hdHair:absorption", {1e6f, 1e6f, 1e6f}}, {"hdHair:longitudinalWidth", {0.1f}}};
    for (const auto& [name, value] : fibres) {
        for (const glm::dvec3& direction : directions) {
            CurvesPrim hair = strand("/hair", 0.0f, {0.5f, 0.5f, 0.5f});
            hair.primvars[name] = constant(name, value);
            Scene scene;
            scene.setCurves(hair);
            scene.setLight(distantFrom(direction));
            glm::vec3 gpu = centrePixel(scene, withModel("marschner", "analytic"));
            for (int c = 0; c < 3; ++c) {
                EXPECT_TRUE(std::isfinite(gpu[c])) << name << " light " << direction.x << direction.y << direction.z;
                // Intensity 2 times f_p, itself below M (<= 1/(2 pi v) at beta 0.5 deg) times A/(2 x 1e-3).
                EXPECT_GE(gpu[c], 0.0f);
                EXPECT_LT(gpu[c], 1e6f);
            }
        }
    }
}

// HdHairAPI values beyond their documented ranges (eta 1, where a fibre
// refracts nothing; a lobe of width 0; negative weights) are clamped to the
// range with one warning naming the prim and primvar, and render as the
// clamped value does.
TEST(ShadingModels, ParametersOutsideTheirRangeAreClampedWithAWarning) {
    const struct {
        const char* name;
        float outside, clamped;
        const char* model;
    } cases[] = {{"hdHair:eta", 1.0f, 1.001f, "marschner"},
                 {"hdHair:longitudinalWidth", 0.0f, 0.1f, "marschner"},
                 {"hdHair:melanin", 1.5f, 1.0f, "marschner"},
                 {"hdHair:kajiyaKay:specular", -2.0f, 0.0f, "kajiyaKay"}};
    for (const auto& c : cases) {
        SCOPED_TRACE(c.name);
        auto render = [&](float value, Diagnostics& diagnostics) {
            CurvesPrim hair = strand("/hair", 0.0f, {0.5f, 0.5f, 0.5f});
            hair.shadingModel = c.model;
            hair.primvars[c.name] = constant(c.name, {value});
            Scene scene;
            scene.setCurves(hair);
            scene.setLight(distantFrom({0.0, 0.0, 1.0}));
            return sharedRenderer().render(scene, camera(), RenderSettings{}, diagnostics);
        };
        Diagnostics outside, inside;
        RenderResult clamped = render(c.outside, outside), expected = render(c.clamped, inside);
        EXPECT_TRUE(inside.warnings().empty());
        ASSERT_EQ(outside.warnings().size(), 1u);
        EXPECT_EQ(outside.warnings()[0].where, std::string("/hair.primvars:") + c.name);
        EXPECT_NE(outside.warnings()[0].message.find("outside the documented range"), std::string::npos)
            << outside.warnings()[0].message;
        EXPECT_EQ(clamped.color.pixels, expected.color.pixels);
    }
}

// One prim whose curves carry different parameters renders as prims that
// carry those parameters each, for per-curve (uniform) primvars.
void expectPerCurveMatchesPerPrim(const std::string& model, const std::string& name, std::vector<float> perCurve,
                                  const RenderSettings& settings, float tolerance) {
    SCOPED_TRACE(name);
    CurvesPrim twoCurves = strand("/hair", 0.0f, {0.5f, 0.4f, 0.3f});
    twoCurves.shadingModel = model;
    twoCurves.curveVertexCounts = {2, 2};
    twoCurves.points = {{-2.0f, 0.4f, 0.0f}, {2.0f, 0.4f, 0.0f}, {-2.0f, -0.4f, 0.0f}, {2.0f, -0.4f, 0.0f}};
    twoCurves.primvars[name] = authoredPrimvar(name, Interpolation::Uniform, 1, perCurve);
    Scene perCurveScene;
    perCurveScene.setCurves(twoCurves);
    Scene perPrimScene;
    const float ys[2] = {0.4f, -0.4f};
    for (int i = 0; i < 2; ++i) {
        CurvesPrim single = strand("/hair" + std::to_string(i), ys[i], {0.5f, 0.4f, 0.3f});
        single.shadingModel = model;
        single.primvars[name] = constant(name, {perCurve[size_t(i)]});
        perPrimScene.setCurves(single);
    }
    for (Scene* scene : {&perCurveScene, &perPrimScene}) scene->setLight(distantFrom({0.3, 0.1, -1.0}));
    RenderResult a = renderScene(perCurveScene, settings), b = renderScene(perPrimScene, settings);
    EXPECT_NE(a.plan.describe().find("per-curve/vertex parameters on 1 prim(s)"), std::string::npos)
        << a.plan.describe();
    CameraView view = camera();
    glm::vec3 rows[2];
    for (int i = 0; i < 2; ++i) {
        int y = int(view.worldToPixel(glm::dvec3(0.0, ys[i], 0.0)).y);
        rows[i] = pixel(a, 32, y);
        glm::vec3 expected = pixel(b, 32, y);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(rows[i][c], expected[c], tolerance * (1e-3f + expected[c])) << i;
    }
    EXPECT_GT(glm::length(rows[0] - rows[1]), 1e-3f) << "the curves differ";
}

TEST(ShadingModels, PerCurveParametersShadeLikePerPrimOnes) {
    // Absorption varies: both scenes per fragment (analytic), which must agree closely...
    expectPerCurveMatchesPerPrim("marschner", "hdHair:melanin", {0.1f, 0.8f}, withModel("marschner", "analytic"),
                                 1e-3f);
    // ...and within the tables' error of per-prim materials drawn from tables.
    expectPerCurveMatchesPerPrim("marschner", "hdHair:melanin", {0.1f, 0.8f}, withModel("marschner"), 0.03f);
    expectPerCurveMatchesPerPrim("marschner", "hdHair:eta", {1.3f, 1.9f}, withModel("marschner", "analytic"), 1e-3f);
    // Longitudinal parameters vary: both from tables.
    expectPerCurveMatchesPerPrim("marschner", "hdHair:longitudinalShift", {-2.0f, -12.0f}, withModel("marschner"),
                                 1e-3f);
    expectPerCurveMatchesPerPrim("kajiyaKay", "hdHair:kajiyaKay:specular", {0.0f, 2.0f}, withModel("kajiyaKay"),
                                 1e-3f);
}

TEST(ShadingModels, PerVertexAbsorptionIsInterpolatedAlongTheStrand) {
    // Vertices at x = -2, 0, 2: a linear curve's vertex absorption at x in
    // [-2, 0] is a0 + u (a1 - a0) with u = (x + 2) / 2 exactly. x: the centre
    // of the pixel nearest -0.6 (the camera is orthographic: x is affine in pixels).
    CameraView view = camera();
    double pixelsPerUnit = view.worldToPixel({1.0, 0.0, 0.0}).x - view.worldToPixel({0.0, 0.0, 0.0}).x;
    glm::dvec3 at = view.worldToPixel(glm::dvec3(-0.6, 0.0, 0.0));
    double x = -0.6 + (std::floor(at.x) + 0.5 - at.x) / pixelsPerUnit;
    const float u = float((x + 2.0) / 2.0);
    const glm::vec3 a0(0.05f, 0.1f, 0.2f), a1(1.5f, 2.0f, 3.0f), a2(0.2f, 0.2f, 0.2f);
    CurvesPrim perVertex = strand("/hair", 0.0f, {0.5f, 0.5f, 0.5f});
    perVertex.shadingModel = "marschner";
    perVertex.curveVertexCounts = {3};
    perVertex.points = {{-2.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, {2.0f, 0.0f, 0.0f}};
    perVertex.primvars["hdHair:absorption"] =
        authoredPrimvar("hdHair:absorption", Interpolation::Vertex, 3, {a0.x, a0.y, a0.z, a1.x, a1.y, a1.z, a2.x, a2.y, a2.z});
    glm::vec3 mixed = a0 + u * (a1 - a0);
    CurvesPrim uniform = strand("/hair", 0.0f, {0.5f, 0.5f, 0.5f});
    uniform.shadingModel = "marschner";
    uniform.primvars["hdHair:absorption"] = constant("hdHair:absorption", {mixed.x, mixed.y, mixed.z});
    RenderSettings settings = withModel("marschner", "analytic");
    glm::vec3 colors[2];
    int i = 0;
    for (const CurvesPrim& prim : {perVertex, uniform}) {
        Scene scene;
        scene.setCurves(prim);
        scene.setLight(distantFrom({0.3, 0.1, -1.0}));  // transmission: absorption shows
        colors[i++] = pixel(renderScene(scene, settings), int(at.x), int(at.y));
    }
    // The fragment's u is interpolated across the tessellated ribbon in single precision.
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(colors[0][c], colors[1][c], 2e-3f * colors[1][c] + 1e-5f) << c;
    EXPECT_GT(colors[1].x, 0.0f);
}

TEST(ShadingModels, PrimsChooseTheirModelAndParametersThroughPrimvars) {
    Scene scene;
    CurvesPrim flat = strand("/flat", 0.6f, {0.2f, 0.4f, 0.8f});
    flat.shadingModel = "flat";  // primvars:hdHair:shadingModel = "flat"
    scene.setCurves(flat);
    CurvesPrim light = strand("/lightHair", 0.0f, {0.5f, 0.5f, 0.5f});
    light.shadingModel = "marschner";
    light.primvars["hdHair:melanin"] = constant("hdHair:melanin", {0.1f});
    scene.setCurves(light);
    CurvesPrim dark = strand("/darkHair", -0.6f, {0.5f, 0.5f, 0.5f});
    dark.shadingModel = "marschner";
    dark.primvars["hdHair:melanin"] = constant("hdHair:melanin", {0.9f});
    scene.setCurves(dark);
    scene.setLight(distantFrom({0.3, 0.1, -1.0}));  // from behind: transmission shows absorption
    RenderSettings settings;  // kajiyaKay by default: every prim chose otherwise
    Diagnostics diagnostics;
    CameraView view = camera();
    RenderResult result = sharedRenderer().render(scene, view, settings, diagnostics);
    EXPECT_TRUE(diagnostics.warnings().empty());
    auto row = [&](float y) { return int(view.worldToPixel(glm::dvec3(0.0, y, 0.0)).y); };
    EXPECT_NEAR(result.color.at(32, row(0.6f), 2), 0.8f, 1e-5f) << "flat shows displayColor";
    float lightHair = result.color.at(32, row(0.0f), 0), darkHair = result.color.at(32, row(-0.6f), 0);
    EXPECT_GT(lightHair, 1.5f * darkHair) << "more melanin absorbs more";
    EXPECT_GT(darkHair, 0.0f);
}
