// The export for Cycles, checked by hand: camera parameters, light units,
// the fibre parameters and the strands' keys. The path tracer's own pixels
// are compared with hdHair's in testenv/tests/testCyclesCalibration.py.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/curves/CatmullRomEvaluation.h"
#include "hdHair/reference/CyclesCamera.h"
#include "hdHair/reference/CyclesLights.h"
#include "hdHair/reference/CyclesScene.h"
#include "hdHair/reference/CyclesStrands.h"
#include "hdHair/reference/PrincipledHair.h"
#include "hdHair/plan/CameraView.h"
#include "hdHair/plan/RenderSettings.h"
#include "hdHair/scene/Scene.h"

using namespace hdhair;

namespace {

CameraView cameraFor(Projection projection, float horizontalOffset = 0.0f) {
    CameraPrim prim;
    prim.path = "/cam";
    prim.projection = projection;
    prim.focalLength = 50.0f;
    prim.horizontalAperture = 40.0f;  // tan(half hfov) = 0.4
    prim.verticalAperture = 20.0f;
    prim.horizontalApertureOffset = horizontalOffset;
    prim.clippingRange = glm::vec2(0.5f, 50.0f);
    prim.worldTransform = glm::translate(glm::dmat4(1.0), glm::dvec3(1.0, 2.0, 10.0));
    return cameraViewFromPrim(prim, 200);
}

CurvesPrim straightCurve(CurveBasis basis, CurveWrap wrap) {
    CurvesPrim prim;
    prim.path = "/hair";
    prim.type = CurveType::Cubic;
    prim.basis = basis;
    prim.wrap = wrap;
    prim.curveVertexCounts = {4};
    prim.points = {{0, 0, 0}, {0, 1, 0}, {0, 2, 0}, {0, 3, 0}};
    Primvar widths;
    widths.name = "widths";
    widths.typeName = "float[]";
    widths.interpolation = Interpolation::Constant;
    widths.tupleSize = 1;
    widths.values = {0.1f};
    prim.primvars["widths"] = widths;
    return prim;
}

}  // namespace

TEST(CyclesCamera, PerspectiveFieldOfViewAndClipping) {
    const CyclesCamera camera = cyclesCamera(cameraFor(Projection::Perspective));
    EXPECT_FALSE(camera.orthographic);
    EXPECT_NEAR(camera.angleX, 2.0 * std::atan(0.4), 1e-9);
    EXPECT_NEAR(camera.shiftX, 0.0, 1e-12);
    EXPECT_NEAR(camera.clipStart, 0.5, 1e-6);
    EXPECT_NEAR(camera.clipEnd, 50.0, 1e-4);
    EXPECT_EQ(camera.width, 200);
    EXPECT_EQ(camera.height, 100);
    EXPECT_NEAR(camera.cameraToWorld[3].x, 1.0, 1e-12);
    EXPECT_NEAR(camera.cameraToWorld[3].z, 10.0, 1e-12);
}

TEST(CyclesCamera, ApertureOffsetIsAShiftInWidths) {
    // An offset of 4 on an aperture of 40 moves the window a tenth of its width.
    const CyclesCamera camera = cyclesCamera(cameraFor(Projection::Perspective, 4.0f));
    EXPECT_NEAR(camera.shiftX, 0.1, 1e-6);
    EXPECT_NEAR(camera.shiftY, 0.0, 1e-9);
}

TEST(CyclesCamera, OrthographicScaleIsTheViewWidth) {
    // Orthographic apertures are tenths of a scene unit: 40 is 4 units wide.
    const CyclesCamera camera = cyclesCamera(cameraFor(Projection::Orthographic, 4.0f));
    EXPECT_TRUE(camera.orthographic);
    EXPECT_NEAR(camera.orthoScale, 4.0, 1e-6);
    EXPECT_NEAR(camera.shiftX, 0.1, 1e-6);
}

TEST(CyclesLights, UnitsFollowWhatHdHairDelivers) {
    Scene scene;
    LightPrim sun;
    sun.path = "/sun";
    sun.type = LightType::Distant;
    sun.intensity = 3.0f;
    sun.exposure = 1.0f;
    sun.angle = 1.0f;
    scene.setLight(sun);
    LightPrim sphere;
    sphere.path = "/sphere";
    sphere.type = LightType::Sphere;
    sphere.intensity = 2.0f;
    sphere.radius = 0.5f;  // I = L π r² = π/2
    scene.setLight(sphere);
    LightPrim rect;
    rect.path = "/rect";
    rect.type = LightType::Rect;
    rect.intensity = 5.0f;
    rect.width = 2.0f;
    rect.height = 0.5f;  // I = L A = 5
    rect.normalize = false;
    scene.setLight(rect);
    LightPrim disk = rect;
    disk.path = "/disk";
    disk.type = LightType::Disk;
    disk.radius = 1.0f;
    disk.normalize = true;  // I = L = 5
    scene.setLight(disk);
    Diagnostics diagnostics;
    const CyclesLighting lighting =
        cyclesLighting(scene, cameraFor(Projection::Perspective), false, false, RenderingSpace::LinearRec709, diagnostics);
    ASSERT_EQ(lighting.lights.size(), 4u);
    std::map<std::string, CyclesLight> byPath;
    for (const CyclesLight& light : lighting.lights) byPath[light.path] = light;
    EXPECT_NEAR(byPath["/sun"].strength.r, 6.0f, 1e-5f);  // S = E = 3 · 2¹
    EXPECT_NEAR(byPath["/sun"].angle, glm::pi<float>() / 180.0f, 1e-6f);
    EXPECT_EQ(byPath["/sphere"].kind, CyclesLight::Kind::Point);
    EXPECT_NEAR(byPath["/sphere"].strength.g, 4.0f * glm::pi<float>() * glm::pi<float>() / 2.0f, 1e-4f);
    EXPECT_NEAR(byPath["/sphere"].radius, 0.5f, 1e-6f);
    EXPECT_EQ(byPath["/rect"].kind, CyclesLight::Kind::Area);
    EXPECT_NEAR(byPath["/rect"].strength.b, 4.0f * 5.0f, 1e-4f);  // P = 4 I
    EXPECT_NEAR(byPath["/rect"].sizeX, 2.0f, 1e-6f);
    EXPECT_NEAR(byPath["/rect"].sizeY, 0.5f, 1e-6f);
    EXPECT_TRUE(byPath["/disk"].disk);
    EXPECT_NEAR(byPath["/disk"].strength.r, 4.0f * 5.0f, 1e-4f);
    EXPECT_NEAR(byPath["/disk"].sizeX, 2.0f, 1e-6f);
    EXPECT_EQ(diagnostics.warningCount(), 0u);
}

TEST(CyclesLights, ACameraLightIsASunFromTheEye) {
    Diagnostics diagnostics;
    const CyclesLighting lighting =
        cyclesLighting(Scene{}, cameraFor(Projection::Perspective), true, false, RenderingSpace::LinearRec709, diagnostics);
    ASSERT_EQ(lighting.lights.size(), 1u);
    const CyclesLight& light = lighting.lights.front();
    EXPECT_EQ(light.kind, CyclesLight::Kind::Sun);
    // As hdHair's: no shadow unless cameraLightShadows=on.
    EXPECT_FALSE(light.castShadow);
    EXPECT_TRUE(cyclesLighting(Scene{}, cameraFor(Projection::Perspective), true, true, RenderingSpace::LinearRec709,
                               diagnostics)
                    .lights.front()
                    .castShadow);
    EXPECT_NEAR(light.strength.r, 1.0f, 1e-6f);
    // It shines down −Z of its frame, which is the camera's viewing direction.
    EXPECT_NEAR(light.lightToWorld[2].z, 1.0, 1e-9);
}

TEST(CyclesLights, AShapedRectWarnsThatCyclesCannotCutIt) {
    Scene scene;
    LightPrim rect;
    rect.path = "/rect";
    rect.type = LightType::Rect;
    rect.coneAngle = 30.0f;
    scene.setLight(rect);
    Diagnostics diagnostics;
    cyclesLighting(scene, cameraFor(Projection::Perspective), false, false, RenderingSpace::LinearRec709, diagnostics);
    ASSERT_EQ(diagnostics.warningCount(), 1u);
    EXPECT_EQ(diagnostics.warnings().front().where, "/rect");
}

TEST(CyclesLights, TheDomeLooksUpUsdsLatlongInBlendersFrame) {
    // USD's latlong centre (+Z of the dome) is Blender's +X; USD's top (+Y)
    // is Blender's +Z; a dome turned 90° about +Y sends +X's texel to world −Z.
    Scene scene;
    LightPrim dome;
    dome.path = "/dome";
    dome.type = LightType::Dome;
    dome.worldTransform = glm::rotate(glm::dmat4(1.0), glm::half_pi<double>(), glm::dvec3(0.0, 1.0, 0.0));
    scene.setLight(dome);
    Diagnostics diagnostics;
    const CyclesLighting lighting =
        cyclesLighting(scene, cameraFor(Projection::Perspective), false, false, RenderingSpace::LinearRec709, diagnostics);
    ASSERT_EQ(lighting.domes.size(), 1u);
    const glm::dmat3& m = lighting.domes.front().worldToTexture;
    const glm::dvec3 up = m * glm::dvec3(0.0, 1.0, 0.0);
    EXPECT_NEAR(up.z, 1.0, 1e-9);
    // World +X is the dome's +Z after the turn (R⁻¹ x = z): Blender's +X, the centre.
    const glm::dvec3 x = m * glm::dvec3(1.0, 0.0, 0.0);
    EXPECT_NEAR(x.x, 1.0, 1e-9);
}

TEST(PrincipledHair, RoughnessMatchesTheLongitudinalVariance) {
    for (float degrees : {2.0f, 5.0f, 7.5f, 10.0f, 20.0f}) {
        const float betaR = degrees * kMarschnerDegrees;
        const double m = principledHairRoughness(betaR);
        const double root = 0.726 * m + 0.812 * m * m + 3.7 * std::pow(m, 20.0);
        EXPECT_NEAR(root * root, marschnerLongitudinalVariance(betaR), 1e-5) << degrees << " degrees";
    }
    EXPECT_EQ(principledHairRoughness(0.0f), 0.0f);
    EXPECT_LE(principledHairRoughness(10.0f), 1.0f);
}

TEST(PrincipledHair, TheCuticleTiltChangesSign) {
    MarschnerParameters marschner;
    const PrincipledHair hair = principledHairFrom(marschner);
    EXPECT_NEAR(hair.offset, 7.5f * kMarschnerDegrees, 1e-6f);
    EXPECT_EQ(hair.absorption, marschner.sigmaA);
    EXPECT_EQ(hair.ior, marschner.eta);
    EXPECT_EQ(hair.coat, 0.0f);
}

TEST(CyclesStrands, KeysLieOnTheCurveHdHairDraws) {
    for (CurveBasis basis : {CurveBasis::Bezier, CurveBasis::Bspline, CurveBasis::CatmullRom}) {
        Diagnostics diagnostics;
        const CurvesPrim prim = straightCurve(basis, CurveWrap::Nonperiodic);
        const PreparedCurves prepared = prepareCurves(prim, diagnostics);
        HairMaterial flat;
        flat.model = ShadingModel::Flat;
        const CyclesStrands strands = cyclesStrands(prepared, flat, 4);
        ASSERT_EQ(strands.keysPerCurve.size(), 1u);
        const size_t spans = prepared.segmentCount();
        ASSERT_EQ(size_t(strands.keysPerCurve[0]), 4 * spans + 1);
        for (size_t s = 0; s < spans; ++s)
            for (int step = 0; step <= 4; ++step) {
                const StrandControlPoint expected = evaluate(prepared.spanControls(s), float(step) / 4.0f);
                const size_t key = 4 * s + size_t(step);
                EXPECT_NEAR(strands.positions[3 * key + 1], expected.position.y, 1e-6f);
                EXPECT_NEAR(strands.radii[key], 0.05f, 1e-6f);
            }
        EXPECT_TRUE(strands.flat);
    }
}

TEST(CyclesStrands, PeriodicCurvesCloseOnTheirFirstKey) {
    Diagnostics diagnostics;
    CurvesPrim prim = straightCurve(CurveBasis::CatmullRom, CurveWrap::Periodic);
    prim.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    const PreparedCurves prepared = prepareCurves(prim, diagnostics);
    HairMaterial hair;
    hair.model = ShadingModel::Marschner;
    const CyclesStrands strands = cyclesStrands(prepared, hair, 2);
    ASSERT_EQ(strands.keysPerCurve.size(), 1u);
    const size_t last = strands.keyCount() - 1;
    for (int axis = 0; axis < 3; ++axis)
        EXPECT_NEAR(strands.positions[3 * last + size_t(axis)], strands.positions[size_t(axis)], 1e-6f);
    EXPECT_FALSE(strands.flat);
}

TEST(CyclesScene, WritesTheArraysWhereTheDescriptionSays) {
    Scene scene;
    scene.setCurves(straightCurve(CurveBasis::CatmullRom, CurveWrap::Pinned));
    Diagnostics diagnostics;
    CyclesFraming framing;
    framing.camera = cameraFor(Projection::Perspective);
    const RenderSettings settings;
    const CyclesScene exported = exportCyclesScene(scene, framing, settings, CyclesRenderOptions{}, diagnostics);
    ASSERT_EQ(exported.strands.size(), 1u);
    // No light on the stage: hdHair's camera light, as a sun.
    ASSERT_EQ(exported.lighting.lights.size(), 1u);
    const std::filesystem::path folder = std::filesystem::temp_directory_path() / "hdhair-testCyclesExport";
    std::filesystem::create_directories(folder);
    writeCyclesScene(exported, folder);
    std::ifstream json(folder / "scene.json");
    const nlohmann::json description = nlohmann::json::parse(json);
    const nlohmann::json& radii = description["curves"][0]["radii"];
    std::ifstream blob(folder / "scene.bin", std::ios::binary);
    blob.seekg(radii["offset"].get<std::streamoff>());
    float first = 0.0f;
    blob.read(reinterpret_cast<char*>(&first), sizeof first);
    EXPECT_EQ(radii["count"].get<size_t>(), exported.keys);
    EXPECT_NEAR(first, 0.05f, 1e-7f);
    EXPECT_EQ(description["render"]["samples"], 64);
    std::filesystem::remove_all(folder);
}

TEST(CyclesScene, ParametersThatVaryBesidesAbsorptionWarnThatTheirMeanIsUsed) {
    CurvesPrim prim = straightCurve(CurveBasis::CatmullRom, CurveWrap::Pinned);
    prim.shadingModel = "marschner";
    Primvar eta;
    eta.name = "hdHair:eta";
    eta.typeName = "float[]";
    eta.interpolation = Interpolation::Vertex;
    eta.values = {1.5f, 1.55f, 1.6f, 1.65f};
    prim.primvars["hdHair:eta"] = eta;
    Scene scene;
    scene.setCurves(prim);
    Diagnostics diagnostics;
    CyclesFraming framing;
    framing.camera = cameraFor(Projection::Perspective);
    const CyclesScene exported = exportCyclesScene(scene, framing, RenderSettings{}, CyclesRenderOptions{}, diagnostics);
    ASSERT_EQ(exported.strands.size(), 1u);
    EXPECT_NEAR(exported.strands.front().hair.ior, 1.575f, 1e-3f);
    bool warned = false;
    for (const Diagnostic& warning : diagnostics.warnings())
        warned = warned || (warning.where == "/hair" && warning.message.find("their mean") != std::string::npos);
    EXPECT_TRUE(warned);
}
