// The renderingSpace setting: authored colours are linear Rec.709 and are
// taken into the rendering space once (ColorSpaces.h's kRec709ToAp1), before
// shading. Where shading is linear in the colours (flat shading; Kajiya-Kay
// and Lambert under white lights; grey fibres under any light), an ACEScg
// frame is therefore the lin_rec709 frame times the matrix, pixel by pixel,
// and the display image through any view of the shipped config is the same
// either way.

#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "DistantLight.h"
#include "HorizontalStrands.h"
#include "OrthographicView.h"
#include "StageRendering.h"
#include "hdHair/image/ColorSpaces.h"
#include "hdHair/image/DisplayTransform.h"
#include "hdHair/image/ImageComparison.h"
#include "hdHair/image/ImageWriter.h"
#include "hdHair/meshes/tests/TestMeshes.h"
#include "hdHair/scene/Scene.h"
#include "hdHair/scene/tests/AuthoredPrimvar.h"

using namespace hdhair;
using namespace hdhair::testenv;
using hdhair::test::authoredPrimvar;

namespace {

// 4 units across at 64 px: 16 px a unit, pixel (0, 0)'s corner at (-2, 2).
constexpr int kPixels = 64;
const glm::vec3 kStrandColor(0.8f, 0.1f, 0.05f);
const glm::vec3 kMeshColor(0.05f, 0.6f, 0.2f);

// A strand 8 px wide across rows 20-27 (z = 0) in front of a unit quad
// covering rows and columns 24-39 (z = -1).
Scene strandOverQuad(glm::vec3 strandColor, glm::vec3 meshColor) {
    Scene scene;
    scene.setCurves(horizontalStrands("/strand", 0, 0, 0.0f, {0.5}, 0.5, strandColor, 1.0f));
    MeshPrim quad = hdhair::test::quadGrid(1, "/quad");
    quad.worldTransform = glm::translate(glm::dmat4(1.0), glm::dvec3(-0.5, -0.5, -1.0));
    quad.primvars["displayColor"] =
        authoredPrimvar("displayColor", Interpolation::Constant, 3, {meshColor.r, meshColor.g, meshColor.b});
    scene.setMesh(quad);
    return scene;
}

Image render(const Scene& scene, const std::string& space, const std::string& shading) {
    RenderSettings settings;
    settings.set("renderingSpace", space);
    settings.set("shadingModel", shading);
    Diagnostics diagnostics;
    RenderResult result =
        sharedRenderer().render(scene, orthographicView(kPixels / 16.0, kPixels), settings, diagnostics);
    EXPECT_TRUE(diagnostics.warnings().empty()) << diagnostics.warnings().front().message;
    return result.color;
}

glm::vec3 pixel(const Image& image, int x, int y) {
    const float* p = image.pixels.data() + 4 * (size_t(y) * size_t(image.width) + size_t(x));
    return glm::vec3(p[0], p[1], p[2]);
}

// `rec709` with every pixel's colour taken through the matrix to ACEScg.
Image toAcesCg(Image rec709) {
    for (size_t p = 0; p < rec709.pixels.size(); p += 4) {
        const glm::vec3 converted =
            toRenderingSpace(RenderingSpace::AcesCg, glm::vec3(rec709.pixels[p], rec709.pixels[p + 1], rec709.pixels[p + 2]));
        for (int c = 0; c < 3; ++c) rec709.pixels[p + size_t(c)] = converted[c];
    }
    return rec709;
}

void expectNear(glm::vec3 actual, glm::vec3 expected, float tolerance, const char* what) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(actual[c], expected[c], tolerance) << what << " channel " << c;
}

TEST(RenderingSpace, TheMatrixKeepsGreyAndIsTheInverseOfOcios) {
    for (size_t row = 0; row < 3; ++row)
        EXPECT_NEAR(kRec709ToAp1[row][0] + kRec709ToAp1[row][1] + kRec709ToAp1[row][2], 1.0, 1e-8);
    for (size_t row = 0; row < 3; ++row)
        for (size_t column = 0; column < 3; ++column) {
            double product = 0.0;
            for (size_t k = 0; k < 3; ++k) product += kAp1ToRec709[row][k] * kRec709ToAp1[k][column];
            EXPECT_NEAR(product, row == column ? 1.0 : 0.0, 2e-8) << row << column;
        }
}

TEST(RenderingSpace, TheMatrixAgreesWithTheShippedConfigsTransforms) {
    // OCIO shows a colour converted by kRec709ToAp1, read as ACEScg, exactly
    // as it shows the original read as lin_rec709: the config's own built-in
    // transforms (not hdHair's matrices) relate the two spaces.
    DisplayTransformOptions options;
    options.mode = ColorCorrectionMode::OpenColorIO;
    options.config = HDHAIR_OCIO_CONFIG;
    options.view = "sRGB";
    options.colorSpace = kAcesCg;
    const DisplayTransform fromAcesCg = DisplayTransform::create(options);
    options.colorSpace = kLinearRec709;
    const DisplayTransform fromRec709 = DisplayTransform::create(options);
    for (const glm::vec3 rec709 : {kStrandColor, kMeshColor, glm::vec3(0.18f)}) {
        const glm::vec3 acescg = toRenderingSpace(RenderingSpace::AcesCg, rec709);
        std::vector<float> a{acescg.r, acescg.g, acescg.b, 1.0f}, b{rec709.r, rec709.g, rec709.b, 1.0f};
        fromAcesCg.apply(a.data(), 1);
        fromRec709.apply(b.data(), 1);
        for (size_t c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], 2e-5) << c;
    }
}

TEST(RenderingSpace, FlatColoursRenderToTheMatrixPredictedValues) {
    const Scene scene = strandOverQuad(kStrandColor, kMeshColor);
    const Image rec709 = render(scene, kLinearRec709, "flat");
    const Image acescg = render(scene, kAcesCg, "flat");
    // By hand: the strand's pixel (32, 24) and the quad's (32, 36).
    expectNear(pixel(rec709, 32, 24), kStrandColor, 1e-3f, "strand, lin_rec709");
    expectNear(pixel(rec709, 32, 36), kMeshColor, 1e-3f, "quad, lin_rec709");
    const glm::vec3 strand = glm::vec3(0.8f * 0.6130974f + 0.1f * 0.3395231f + 0.05f * 0.0473795f,
                                       0.8f * 0.0701937f + 0.1f * 0.9163539f + 0.05f * 0.0134524f,
                                       0.8f * 0.0206156f + 0.1f * 0.1095698f + 0.05f * 0.8698146f);
    expectNear(pixel(acescg, 32, 24), strand, 1e-3f, "strand, ACEScg");
    expectNear(pixel(acescg, 32, 36), toRenderingSpace(RenderingSpace::AcesCg, kMeshColor), 1e-3f, "quad, ACEScg");
    EXPECT_GT(strand.r - strand.g, 0.3f) << "still a saturated red, not grey";
}

TEST(RenderingSpace, LitFramesAreTheMatrixTimesTheRec709FrameWhereShadingIsLinear) {
    // Saturated hair and mesh under a white light, and grey hair and mesh
    // under a saturated light: Kajiya-Kay and Lambert are linear in either
    // factor when the other is grey, so the whole frame converts exactly.
    Scene coloured = strandOverQuad(kStrandColor, kMeshColor);
    coloured.setLight(distantLightFrom({0.3, 0.4, 1.0}));
    Scene greyUnderColour = strandOverQuad(glm::vec3(0.4f), glm::vec3(0.6f));
    LightPrim light = distantLightFrom({0.3, 0.4, 1.0});
    light.color = glm::vec3(1.0f, 0.3f, 0.1f);
    greyUnderColour.setLight(light);
    for (const Scene* scene : {&coloured, &greyUnderColour}) {
        const ImageComparison comparison = compareImages(render(*scene, kAcesCg, "kajiyaKay"),
                                                         toAcesCg(render(*scene, kLinearRec709, "kajiyaKay")),
                                                         exactWithin(2e-3));
        EXPECT_TRUE(comparison.passed) << comparison.description;
        EXPECT_GT(comparison.coveredPixels, 300u);
    }
}

TEST(RenderingSpace, AGreyStageRendersTheSameGreyInEitherSpace) {
    // widths.usda: grey strands (0.8) under the camera light, shadowed.
    StageRenderRequest request;
    request.stagePath = "testenv/stages/widths.usda";
    request.imageWidth = 96;
    const Image rec709 = renderStage(request).result.color;
    request.settings = {"renderingSpace=ACEScg"};
    const Image acescg = renderStage(request).result.color;
    const ImageComparison comparison = compareImages(acescg, rec709, exactWithin(2e-3));
    EXPECT_TRUE(comparison.passed) << comparison.description;
    EXPECT_GT(comparison.coveredPixels, 500u);
}

TEST(RenderingSpace, DisplayImagesThroughTheSrgbAndAcesViewsAgreeEitherWay) {
    // A coloured groom under the (white) camera light: each render shown
    // from its own rendering space gives the same display image.
    StageRenderRequest request;
    request.stagePath = "examples/wavy_strands.usda";
    request.imageWidth = 96;
    const Image rec709 = renderStage(request).result.color;
    request.settings = {"renderingSpace=ACEScg"};
    const Image acescg = renderStage(request).result.color;
    // (The Raw view shows values as they are, from whichever space: it is
    // the one view under which the two renders differ, by design.)
    for (const char* view : {"sRGB", "ACES 1.0 SDR-video"}) {
        DisplayTransformOptions options;
        options.mode = ColorCorrectionMode::OpenColorIO;
        options.config = HDHAIR_OCIO_CONFIG;
        options.view = view;
        options.renderingSpace = kLinearRec709;
        const Image shownRec709 = displayImage(rec709, DisplayTransform::create(options), true);
        options.renderingSpace = kAcesCg;
        const Image shownAcesCg = displayImage(acescg, DisplayTransform::create(options), true);
        const ImageComparison comparison = compareImages(shownAcesCg, shownRec709, exactWithin(3e-3));
        EXPECT_TRUE(comparison.passed) << view << ": " << comparison.description;
    }
    // And the frames themselves differ: ACEScg is not a relabelled Rec.709.
    EXPECT_FALSE(compareImages(acescg, rec709, exactWithin(5e-3)).passed);
}

}  // namespace
