// The GPU shades as the CPU models say: a single straight strand under one
// distant light, seen by an orthographic camera, so the tangent, the eye and
// the light direction at its centre pixel are known exactly. And hair
// parameters chosen per prim through HdHairAPI primvars.

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "StageRendering.h"
#include "hdHair/render/CameraView.h"
#include "hdHair/render/HairMaterial.h"
#include "hdHair/scene/Scene.h"
#include "hdHair/shading/KajiyaKay.h"
#include "hdHair/shading/MarschnerTables.h"
#include "hdHair/shading/ShadingLight.h"

using namespace hdhair;
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

CameraView camera() {
    CameraPrim prim;
    prim.projection = Projection::Orthographic;
    prim.horizontalAperture = prim.verticalAperture = 24.0f;
    prim.clippingRange = {0.1f, 100.0f};
    prim.worldTransform = glm::translate(glm::dmat4(1.0), glm::dvec3(0, 0, 10));
    return cameraViewFromPrim(prim, 64);
}

// A distant light shining from `towardsLight` (its -Z turned to -towardsLight).
LightPrim distantFrom(glm::dvec3 towardsLight) {
    LightPrim light;
    light.path = "/light";
    light.intensity = 2.0f;
    towardsLight = glm::normalize(towardsLight);
    glm::dvec3 z = towardsLight;
    glm::dvec3 x = glm::normalize(glm::cross(std::abs(z.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0), z));
    glm::dvec3 y = glm::cross(z, x);
    light.worldTransform = glm::dmat4(glm::dvec4(x, 0), glm::dvec4(y, 0), glm::dvec4(z, 0), glm::dvec4(0, 0, 0, 1));
    return light;
}

glm::vec3 centrePixel(const Scene& scene, const std::string& model) {
    RenderSettings settings;
    settings.set("shadingModel", model);
    Diagnostics diagnostics;
    RenderResult result = sharedRenderer().render(scene, camera(), settings, diagnostics);
    EXPECT_EQ(result.stats.transparency, "opaque");
    return glm::vec3(result.color.at(32, 32, 0), result.color.at(32, 32, 1), result.color.at(32, 32, 2));
}

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

TEST(ShadingModels, GpuMarschnerMatchesTheCpuTabledModel) {
    const glm::vec3 color(0.5f, 0.3f, 0.15f);
    for (const glm::dvec3& direction : kLightDirections) {
        Scene scene;
        CurvesPrim hair = strand("/hair", 0.0f, color);
        scene.setCurves(hair);
        scene.setLight(distantFrom(direction));
        glm::vec3 gpu = centrePixel(scene, "marschner");
        RenderSettings settings;
        settings.set("shadingModel", "marschner");
        Diagnostics diagnostics;
        HairMaterial material = hairMaterialFor(hair, settings, diagnostics);
        MarschnerTables tables = buildMarschnerTables(material.marschner);
        MarschnerLobes lobes = evaluateMarschnerTabled({1, 0, 0}, glm::vec3(glm::normalize(direction)), {0, 0, 1},
                                                       material.marschner, tables);
        glm::vec3 cpu = 2.0f * lobes.radiance();
        // Half-float tables are the same texels on both sides; the GPU's
        // bilinear weights carry 8 bits of fraction (GL's minimum).
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(gpu[c], cpu[c], 2e-3f + 0.02f * cpu[c]) << c << " light " << direction.x;
    }
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
