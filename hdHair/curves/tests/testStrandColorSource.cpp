// A bound UsdPreviewSurface colours strands as Storm shows them: constants,
// primvar readers, and inputs hdHair cannot evaluate.

#include <gtest/gtest.h>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/curves/PreparedCurves.h"
#include "hdHair/curves/StrandColorSource.h"
#include "hdHair/scene/CurvesPrim.h"
#include "hdHair/scene/MaterialPrim.h"
#include "hdHair/scene/tests/AuthoredPrimvar.h"

using namespace hdhair;
using hdhair::test::authoredPrimvar;

namespace {

// Two linear curves with a per-curve displayColor (red, green) and a
// per-curve "hairColor" (blue, white).
CurvesPrim twoCurves() {
    CurvesPrim prim;
    prim.path = "/hair";
    prim.type = CurveType::Linear;
    prim.curveVertexCounts = {2, 2};
    prim.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
    prim.primvars["displayColor"] = authoredPrimvar("displayColor", Interpolation::Uniform, 3, {1, 0, 0, 0, 1, 0});
    prim.primvars["hairColor"] = authoredPrimvar("hairColor", Interpolation::Uniform, 3, {0, 0, 1, 1, 1, 1});
    prim.materialBinding = "/Looks/hair";
    return prim;
}

MaterialPrim previewSurface() {
    MaterialPrim material;
    material.path = "/Looks/hair";
    material.surfaceShaderId = "UsdPreviewSurface";
    return material;
}

PreparedCurves prepare(const CurvesPrim& prim, const MaterialPrim* material, Diagnostics& diagnostics) {
    const StrandColorSource colors = strandColorSource(prim, material, diagnostics);
    return prepareCurves(prim, diagnostics, {}, &colors);
}

// Every curve here is one span.
glm::vec3 curveColor(const PreparedCurves& prepared, size_t curve) { return prepared.spanControls(curve)[1].color; }

}  // namespace

TEST(StrandColorSource, WithoutAMaterialThePrimsPrimvarsColourTheStrands) {
    Diagnostics diagnostics;
    CurvesPrim prim = twoCurves();
    const PreparedCurves prepared = prepare(prim, nullptr, diagnostics);
    EXPECT_EQ(curveColor(prepared, 0), glm::vec3(1, 0, 0));
    EXPECT_EQ(curveColor(prepared, 1), glm::vec3(0, 1, 0));
    EXPECT_TRUE(prepared.colorAuthored);
    // The same as preparing with no colour source at all.
    const PreparedCurves plain = prepareCurves(prim, diagnostics);
    EXPECT_EQ(curveColor(plain, 1), glm::vec3(0, 1, 0));
    prim.primvars.erase("displayColor");
    EXPECT_FALSE(prepare(prim, nullptr, diagnostics).colorAuthored);
    EXPECT_TRUE(diagnostics.warnings().empty());
}

TEST(StrandColorSource, PreviewSurfaceConstantsReplaceDisplayColorAndOpacity) {
    Diagnostics diagnostics;
    MaterialPrim material = previewSurface();
    material.diffuseColor.value = {0.6f, 0.3f, 0.1f};
    material.opacity.value = {0.5f};
    const PreparedCurves prepared = prepare(twoCurves(), &material, diagnostics);
    for (const StrandControlPoint& point : prepared.controlPoints) {
        EXPECT_EQ(point.color, glm::vec3(0.6f, 0.3f, 0.1f));
        EXPECT_EQ(point.opacity, 0.5f);
    }
    EXPECT_TRUE(prepared.colorAuthored);
    // Unauthored inputs are UsdPreviewSurface's defaults: 0.18 grey, opaque.
    const MaterialPrim defaults = previewSurface();
    const PreparedCurves grey = prepare(twoCurves(), &defaults, diagnostics);
    EXPECT_EQ(curveColor(grey, 1), glm::vec3(0.18f));
    EXPECT_EQ(grey.controlPoints[1].opacity, 1.0f);
    EXPECT_TRUE(diagnostics.warnings().empty());
}

TEST(StrandColorSource, APrimvarReaderReadsItsPrimvarOrGivesItsFallback) {
    Diagnostics diagnostics;
    MaterialPrim material = previewSurface();
    material.diffuseColor = {MaterialInput::Source::Primvar, {0.2f, 0.2f, 0.9f}, "hairColor", {}};
    const PreparedCurves read = prepare(twoCurves(), &material, diagnostics);
    EXPECT_EQ(curveColor(read, 0), glm::vec3(0, 0, 1));
    EXPECT_EQ(curveColor(read, 1), glm::vec3(1, 1, 1));
    material.diffuseColor.primvar = "notAuthored";
    const PreparedCurves fallback = prepare(twoCurves(), &material, diagnostics);
    EXPECT_EQ(curveColor(fallback, 0), glm::vec3(0.2f, 0.2f, 0.9f));
    EXPECT_FALSE(fallback.colorAuthored);
    EXPECT_TRUE(diagnostics.warnings().empty());
}

TEST(StrandColorSource, InputsHdHairCannotEvaluateKeepThePrimsColoursWithAWarning) {
    Diagnostics diagnostics;
    MaterialPrim material = previewSurface();
    material.diffuseColor = {MaterialInput::Source::Unsupported, {}, {}, "UsdUVTexture"};
    material.opacity.value = {0.5f, 0.5f};  // a float input given two components
    const PreparedCurves prepared = prepare(twoCurves(), &material, diagnostics);
    EXPECT_EQ(curveColor(prepared, 1), glm::vec3(0, 1, 0));
    EXPECT_EQ(prepared.controlPoints[1].opacity, 1.0f);
    ASSERT_EQ(diagnostics.warningCount(), 2u);
    EXPECT_EQ(diagnostics.warnings()[0].where, "/Looks/hair.inputs:diffuseColor");
    EXPECT_EQ(diagnostics.warnings()[0].message,
              "connected to UsdUVTexture, which hdHair does not evaluate; using the prim's displayColor");
    EXPECT_EQ(diagnostics.warnings()[1].where, "/Looks/hair.inputs:opacity");
    EXPECT_EQ(diagnostics.warnings()[1].message, "expected 1 value, found 2; using the prim's displayOpacity");
}

TEST(StrandColorSource, OtherSurfaceShadersLeaveThePrimsColours) {
    // Renderer-specific hair shaders (PxrMarschnerHair, standard_hair...)
    // are not read: hdHair's own models shade, from displayColor.
    Diagnostics diagnostics;
    MaterialPrim material = previewSurface();
    material.surfaceShaderId = "PxrMarschnerHair";
    material.diffuseColor.value = {0.6f, 0.3f, 0.1f};
    const PreparedCurves prepared = prepare(twoCurves(), &material, diagnostics);
    EXPECT_EQ(curveColor(prepared, 0), glm::vec3(1, 0, 0));
    EXPECT_TRUE(diagnostics.warnings().empty());
}
