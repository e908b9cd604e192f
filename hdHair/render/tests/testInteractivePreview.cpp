// What a preview is (InteractivePreview.h): the full frame's settings made
// cheap, the same view with fewer pixels enlarged back by whole pixels, fewer
// curves drawn, and how far it is cut down to fit the budget.

#include <stdexcept>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "HairTuft.h"
#include "hdHair/base/Diagnostics.h"
#include "hdHair/render/InteractivePreview.h"
#include "hdHair/render/Renderer.h"

using namespace hdhair;

TEST(InteractivePreview, SettingsAreCoarseWithFewBinsAndNoShadows) {
    RenderSettings full;
    full.setComplexity(Complexity::High);
    full.set("transparency", "exact");
    full.set("marschner:azimuthal", "analytic");
    full.set("msaaSamples", "4");
    full.set("kajiyaKay:specular", "0.5");
    const RenderSettings preview = previewSettings(full);
    EXPECT_EQ(preview.getFloat("pixelsPerSegment"), 16.0);
    EXPECT_EQ(preview.getFloat("tessellationTolerance"), 1.0);
    EXPECT_EQ(preview.getInt("maxSegmentsPerSpan"), 4);
    EXPECT_EQ(preview.getToken("transparency"), "binSorted");
    EXPECT_EQ(preview.getInt("sortBins"), 16);
    EXPECT_EQ(preview.getToken("shadowMode"), "off");
    EXPECT_EQ(preview.getInt("lightsPerPass"), 16);
    EXPECT_EQ(preview.getInt("msaaSamples"), 0);
    EXPECT_EQ(preview.getToken("marschner:azimuthal"), "tables");
    EXPECT_FALSE(preview.getBool("passTimings"));
    // A preview of the reference preset is as cheap: one sample a pixel,
    // binSorted, tables, no shadows, whatever the preset asked for.
    const RenderSettings reference = previewSettings(RenderSettings::fromAssignments(Complexity::Low, {"quality=reference"}));
    EXPECT_EQ(reference.getInt("supersampling"), 1);
    EXPECT_EQ(reference.getToken("transparency"), "binSorted");
    EXPECT_EQ(reference.getToken("shadowMode"), "off");
    EXPECT_EQ(reference.getToken("marschner:azimuthal"), "tables");
    EXPECT_EQ(reference.getFloat("tessellationTolerance"), 1.0);
    // What it looks like stays: shading, the space, the mesh refinement.
    EXPECT_EQ(preview.getFloat("kajiyaKay:specular"), 0.5);
    EXPECT_EQ(preview.getInt("meshRefineLevel"), full.getInt("meshRefineLevel"));
    EXPECT_EQ(preview.getToken("renderingSpace"), full.getToken("renderingSpace"));
    // Settings already coarser than a preview's are kept.
    RenderSettings coarse;
    coarse.set("pixelsPerSegment", "40");
    coarse.set("maxSegmentsPerSpan", "2");
    coarse.set("sortBins", "4");
    coarse.set("transparency", "unsorted");
    EXPECT_EQ(previewSettings(coarse).getFloat("pixelsPerSegment"), 40.0);
    EXPECT_EQ(previewSettings(coarse).getInt("maxSegmentsPerSpan"), 2);
    EXPECT_EQ(previewSettings(coarse).getInt("sortBins"), 4);
    EXPECT_EQ(previewSettings(coarse).getToken("transparency"), "unsorted");
}

TEST(InteractivePreview, FewerPixelsSeeTheSameViewAndAreEnlargedByWholePixels) {
    const CameraView full = testscenes::tuftCamera(0.0, 100);
    const CameraView quarter = previewCamera(full, 4);
    EXPECT_EQ(quarter.imageWidth, 25);
    EXPECT_EQ(quarter.imageHeight, full.imageHeight / 4);
    EXPECT_EQ(quarter.view, full.view);
    EXPECT_EQ(quarter.projection, full.projection);
    EXPECT_EQ(previewCamera(full, 1000).imageWidth, 1);

    RenderResult preview;
    preview.color = Image(2, 1, 4);
    preview.color.pixels = {1, 0, 0, 1, 0, 1, 0, 0.5f};
    preview.depth = Image(2, 1, 1);
    preview.depth.pixels = {0.25f, 1.0f};
    preview.primIds = {7, -1};
    enlargePreview(preview, 4, 2);
    ASSERT_EQ(preview.color.width, 4);
    ASSERT_EQ(preview.color.height, 2);
    for (int y = 0; y < 2; ++y) {
        EXPECT_EQ(preview.color.at(1, y, 0), 1.0f);
        EXPECT_EQ(preview.color.at(2, y, 1), 1.0f);
        EXPECT_EQ(preview.color.at(3, y, 3), 0.5f);
    }
    EXPECT_EQ(preview.depth.pixels, (std::vector<float>{0.25f, 0.25f, 1, 1, 0.25f, 0.25f, 1, 1}));
    EXPECT_EQ(preview.primIds, (std::vector<int32_t>{7, 7, -1, -1, 7, 7, -1, -1}));
    EXPECT_TRUE(preview.instanceIds.empty());  // not asked for: still none
}

TEST(InteractivePreview, TheBudgetMovesALevelPerDoublingOverItAndComesBack) {
    PreviewBudget budget;
    EXPECT_EQ(budget.level(), 0);
    // Before any preview, the full frame places the first: 2 seconds against
    // 100 ms is 20 times over, ceil(log2 20) = 5 levels: 1/8 of the pixels
    // across and every 4th curve.
    budget.recordFullFrame(2000.0, 100.0);
    EXPECT_EQ(budget.level(), 5);
    EXPECT_EQ(budget.pixelDivisor(), 8);
    EXPECT_EQ(budget.curveStride(), 4);
    budget.recordPreview(90.0, 100.0);  // within the budget: stays
    EXPECT_EQ(budget.level(), 5);
    budget.recordFullFrame(100000.0, 100.0);  // previews are measured now: full frames no longer count
    EXPECT_EQ(budget.level(), 5);
    budget.recordPreview(350.0, 100.0);  // 3.5 times over: two levels
    EXPECT_EQ(budget.level(), 7);
    budget.recordPreview(5000.0, 100.0);  // never past the top
    EXPECT_EQ(budget.level(), PreviewBudget::kTopLevel);
    EXPECT_EQ(budget.curveStride(), 16);
    budget.recordPreview(50.0, 100.0);  // between a third of the budget and the budget: stays
    EXPECT_EQ(budget.level(), 7);
    for (int level = 6; level >= 0; --level) {
        budget.recordPreview(20.0, 100.0);  // well under: a level down each time
        EXPECT_EQ(budget.level(), level);
    }
    EXPECT_EQ(budget.pixelDivisor(), 1);
    EXPECT_EQ(budget.curveStride(), 1);
    budget.recordPreview(20.0, 100.0);
    EXPECT_EQ(budget.level(), 0);
}

TEST(InteractivePreview, AThinnedPreviewDrawsEveryNthCurveOnEveryPath) {
    // One prim of eight horizontal strands, one a pixel row band each; a
    // preview keeping every 4th curve draws curves 0 and 4 and no other.
    CurvesPrim prim;
    prim.path = "/rows";
    prim.primId = 3;
    prim.type = CurveType::Linear;
    const std::vector<float> heights = {0.8f, 0.6f, 0.4f, 0.2f, -0.2f, -0.4f, -0.6f, -0.8f};
    for (float y : heights) {
        prim.curveVertexCounts.push_back(3);  // two segments a curve
        for (float x : {-1.0f, 0.0f, 1.0f}) prim.points.push_back({x, y, 0.0f});
    }
    prim.primvars["widths"].name = "widths";
    prim.primvars["widths"].values = {0.1f};
    Scene scene;
    scene.setCurves(prim);
    CameraPrim lens;
    lens.projection = Projection::Orthographic;
    lens.horizontalAperture = lens.verticalAperture = 24.0f;
    lens.worldTransform = glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 0.0, 5.0));
    const CameraView camera = cameraViewFromPrim(lens, 96);
    Renderer renderer(gl::defaultGlBackend());
    Diagnostics diagnostics;
    for (const char* path : {"binSorted", "unsorted", "opaque"}) {
        RenderSettings full;
        full.set("transparency", path);
        FrameControl control;
        control.preview = true;
        control.previewCurveStride = 4;
        const RenderResult result =
            renderer.render(scene, camera, previewSettings(full), diagnostics, RenderOutputs{true}, control);
        for (size_t curve = 0; curve < heights.size(); ++curve) {
            const int row = int(camera.worldToPixel(glm::dvec3(0.0, heights[curve], 0.0)).y);
            const int32_t element = result.elementIds[size_t(row) * 96 + 48];
            EXPECT_EQ(element, curve % 4 == 0 ? int32_t(curve) : -1) << path << ", curve " << curve;
        }
    }
    // Only previews leave curves out.
    FrameControl notAPreview;
    notAPreview.previewCurveStride = 2;
    EXPECT_THROW(renderer.render(scene, camera, RenderSettings{}, diagnostics, {}, notAPreview), std::invalid_argument);
    EXPECT_TRUE(diagnostics.warnings().empty());
}
