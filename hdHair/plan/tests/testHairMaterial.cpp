// Hair materials from HdHairAPI primvars: what varies per curve or per vertex
// is found, carried to the control points, and routed to the per-fragment
// Marschner path only where tables cannot serve.

#include <cmath>

#include <gtest/gtest.h>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/curves/PreparedCurves.h"
#include "hdHair/plan/HairMaterial.h"
#include "hdHair/plan/RenderSettings.h"
#include "hdHair/scene/CurvesPrim.h"
#include "hdHair/scene/tests/AuthoredPrimvar.h"

using namespace hdhair;
using hdhair::test::authoredPrimvar;

namespace {

// Two linear curves of two vertices each: one segment a curve.
CurvesPrim twoStrands(const std::string& model) {
    CurvesPrim prim;
    prim.path = "/hair";
    prim.type = CurveType::Linear;
    prim.curveVertexCounts = {2, 2};
    prim.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
    prim.shadingModel = model;
    return prim;
}

struct Resolved {
    PreparedCurves prepared;
    HairMaterial material;
};

Resolved resolve(const CurvesPrim& prim, Diagnostics& diagnostics, const std::string& azimuthal = "auto") {
    RenderSettings settings;
    settings.set("marschner:azimuthal", azimuthal);
    Resolved result;
    result.prepared = prepareCurves(prim, diagnostics, hairParameterPrimvars());
    result.material = hairMaterialFor(prim, result.prepared, settings, diagnostics);
    return result;
}

}  // namespace

TEST(HairMaterial, ConstantParametersMakeASharedTabledMaterial) {
    CurvesPrim prim = twoStrands("marschner");
    prim.primvars["hdHair:melanin"] = authoredPrimvar("hdHair:melanin", Interpolation::Constant, 1, {0.6f});
    Diagnostics diagnostics;
    Resolved r = resolve(prim, diagnostics);
    EXPECT_FALSE(r.material.perPoint());
    EXPECT_TRUE(r.material.usesTables());
    EXPECT_TRUE(r.material.perPointPrim.empty()) << "shared with any prim of equal parameters";
    EXPECT_EQ(r.material.marschner.sigmaA, marschnerSigmaAFromMelanin(0.6f));
    EXPECT_TRUE(diagnostics.warnings().empty());
}

TEST(HairMaterial, PerCurveValuesThatAreAllEqualCountAsConstant) {
    CurvesPrim prim = twoStrands("marschner");
    prim.primvars["hdHair:eta"] = authoredPrimvar("hdHair:eta", Interpolation::Uniform, 1, {1.6f, 1.6f});
    Diagnostics diagnostics;
    Resolved r = resolve(prim, diagnostics);
    EXPECT_FALSE(r.material.perPoint());
    EXPECT_FLOAT_EQ(r.material.marschner.eta, 1.6f);
}

TEST(HairMaterial, PerCurveMelaninVariesAbsorptionAndGoesAnalytic) {
    CurvesPrim prim = twoStrands("marschner");
    prim.primvars["hdHair:melanin"] = authoredPrimvar("hdHair:melanin", Interpolation::Uniform, 1, {0.1f, 0.9f});
    Diagnostics diagnostics;
    Resolved r = resolve(prim, diagnostics);
    EXPECT_EQ(r.material.varies, unsigned(kAbsorptionVaries));
    EXPECT_TRUE(r.material.analyticAzimuthal) << "no per-material table fits varying absorption";
    EXPECT_EQ(r.material.perPointPrim, "/hair");
    EXPECT_TRUE(diagnostics.warnings().empty());

    std::vector<glm::vec4> points = hairParameterPoints(r.material, r.prepared);
    ASSERT_EQ(points.size(), 2 * r.prepared.controlPoints.size());
    ASSERT_EQ(r.prepared.segmentCount(), 2u);
    for (size_t k = 0; k < 8; ++k) {
        glm::vec3 expected = marschnerSigmaAFromMelanin(k < 4 ? 0.1f : 0.9f);
        EXPECT_EQ(glm::vec3(points[2 * k]), expected) << k;
        EXPECT_FLOAT_EQ(points[2 * k].w, 1.55f) << "eta keeps the default";
        EXPECT_FLOAT_EQ(points[2 * k + 1].x, r.material.marschner.alpha.x);
        EXPECT_FLOAT_EQ(points[2 * k + 1].y, r.material.marschner.beta.x);
    }
}

TEST(HairMaterial, VaryingLongitudinalParametersKeepTheTables) {
    CurvesPrim prim = twoStrands("marschner");
    prim.primvars["hdHair:longitudinalShift"] =
        authoredPrimvar("hdHair:longitudinalShift", Interpolation::Vertex, 1, {-10.0f, -5.0f, -10.0f, -5.0f});
    Diagnostics diagnostics;
    Resolved r = resolve(prim, diagnostics);
    EXPECT_EQ(r.material.varies, unsigned(kLongitudinalVaries));
    EXPECT_TRUE(r.material.usesTables()) << "tables do not depend on the longitudinal terms";
    std::vector<glm::vec4> points = hairParameterPoints(r.material, r.prepared);
    // A linear span's vertex values become Catmull-Rom controls (2a-b, a, b, 2b-a).
    const float degree = kMarschnerDegrees;
    EXPECT_NEAR(points[2 * 1 + 1].x, -10.0f * degree, 1e-6f);
    EXPECT_NEAR(points[2 * 2 + 1].x, -5.0f * degree, 1e-6f);
    EXPECT_NEAR(points[2 * 0 + 1].x, -15.0f * degree, 1e-6f);
}

TEST(HairMaterial, PerVertexColourVariesAbsorptionOnlyForMarschner) {
    CurvesPrim prim = twoStrands("marschner");
    prim.primvars["displayColor"] =
        authoredPrimvar("displayColor", Interpolation::Vertex, 3, {0.8f, 0.6f, 0.4f, 0.8f, 0.6f, 0.4f, 0.2f, 0.1f, 0.05f,
                                                           0.2f, 0.1f, 0.05f});
    Diagnostics diagnostics;
    EXPECT_EQ(resolve(prim, diagnostics).material.varies, unsigned(kAbsorptionVaries));
    prim.primvars["hdHair:melanin"] = authoredPrimvar("hdHair:melanin", Interpolation::Constant, 1, {0.5f});
    EXPECT_EQ(resolve(prim, diagnostics).material.varies, unsigned(kNothingVaries)) << "melanin takes precedence";
    prim.shadingModel = "kajiyaKay";
    prim.primvars.erase("hdHair:melanin");
    EXPECT_EQ(resolve(prim, diagnostics).material.varies, unsigned(kNothingVaries))
        << "Kajiya-Kay reads colour per fragment anyway";
}

TEST(HairMaterial, KajiyaKayWeightsPerCurve) {
    CurvesPrim prim = twoStrands("kajiyaKay");
    prim.primvars["hdHair:kajiyaKay:specular"] =
        authoredPrimvar("hdHair:kajiyaKay:specular", Interpolation::Uniform, 1, {0.0f, 1.0f});
    Diagnostics diagnostics;
    Resolved r = resolve(prim, diagnostics);
    EXPECT_EQ(r.material.varies, unsigned(kKajiyaKayVaries));
    EXPECT_FALSE(r.material.analyticAzimuthal);
    std::vector<glm::vec4> points = hairParameterPoints(r.material, r.prepared);
    EXPECT_EQ(points[0], glm::vec4(1.0f, 0.0f, 60.0f, 0.0f)) << "settings' Kd and p, the curve's Ks";
    EXPECT_EQ(points[2 * 4], glm::vec4(1.0f, 1.0f, 60.0f, 0.0f));
}

TEST(HairMaterial, ForcedTablesUseTheMeanAbsorption) {
    CurvesPrim prim = twoStrands("marschner");
    prim.primvars["hdHair:absorption"] =
        authoredPrimvar("hdHair:absorption", Interpolation::Uniform, 3, {0.2f, 0.4f, 0.6f, 1.0f, 1.2f, 1.4f});
    prim.primvars["hdHair:longitudinalWidth"] = authoredPrimvar("hdHair:longitudinalWidth", Interpolation::Uniform, 1, {5, 9});
    Diagnostics diagnostics;
    Resolved r = resolve(prim, diagnostics, "tables");
    EXPECT_EQ(r.material.varies, unsigned(kLongitudinalVaries)) << "what tables cannot vary is held at its mean";
    EXPECT_TRUE(r.material.usesTables());
    EXPECT_NEAR(r.material.marschner.sigmaA.x, 0.6f, 1e-6f);
    EXPECT_NEAR(r.material.marschner.sigmaA.z, 1.0f, 1e-6f);
}

TEST(HairMaterial, TheAnalyticSettingRoutesEveryMarschnerPrim) {
    CurvesPrim prim = twoStrands("marschner");
    Diagnostics diagnostics;
    EXPECT_FALSE(resolve(prim, diagnostics).material.analyticAzimuthal);
    Resolved r = resolve(prim, diagnostics, "analytic");
    EXPECT_TRUE(r.material.analyticAzimuthal);
    EXPECT_FALSE(r.material.perPoint());
    prim.shadingModel = "kajiyaKay";
    EXPECT_FALSE(resolve(prim, diagnostics, "analytic").material.analyticAzimuthal);
}

TEST(HairMaterial, AnUnusablePrimvarIsReportedAndFallsBackToTheSchemaDefault) {
    CurvesPrim prim = twoStrands("marschner");
    prim.primvars["hdHair:eta"] = authoredPrimvar("hdHair:eta", Interpolation::Vertex, 1, {1.4f, 1.5f, 1.6f});  // needs 4
    prim.primvars["hdHair:melanin"] = authoredPrimvar("hdHair:melanin", Interpolation::Uniform, 1, {0.2f, std::nanf("")});
    Diagnostics diagnostics;
    Resolved r = resolve(prim, diagnostics);
    EXPECT_FLOAT_EQ(r.material.marschner.eta, 1.55f);
    ASSERT_EQ(diagnostics.warnings().size(), 2u);
    bool namesEta = false, namesMelanin = false;
    for (const auto& warning : diagnostics.warnings()) {
        namesEta = namesEta || warning.where == "/hair.primvars:hdHair:eta";
        namesMelanin = namesMelanin || warning.where == "/hair.primvars:hdHair:melanin";
    }
    EXPECT_TRUE(namesEta && namesMelanin);
    // The non-finite melanin became the default 0.3 on the second curve only.
    std::vector<glm::vec4> points = hairParameterPoints(r.material, r.prepared);
    EXPECT_EQ(glm::vec3(points[2 * 4]), marschnerSigmaAFromMelanin(0.3f));
    EXPECT_EQ(glm::vec3(points[0]), marschnerSigmaAFromMelanin(0.2f));
}
