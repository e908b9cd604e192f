// What a preview is (InteractivePreview.h): the full frame's settings made
// cheap, the same view with fewer pixels enlarged back by whole pixels, and
// a pixel count chosen to fit the budget.

#include <gtest/gtest.h>

#include "HairTuft.h"
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
    EXPECT_EQ(preview.getInt("maxSegmentsPerSpan"), 4);
    EXPECT_EQ(preview.getToken("transparency"), "binSorted");
    EXPECT_EQ(preview.getInt("sortBins"), 16);
    EXPECT_EQ(preview.getToken("shadowMode"), "off");
    EXPECT_EQ(preview.getInt("lightsPerPass"), 16);
    EXPECT_EQ(preview.getInt("msaaSamples"), 0);
    EXPECT_EQ(preview.getToken("marschner:azimuthal"), "tables");
    EXPECT_FALSE(preview.getBool("passTimings"));
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

TEST(InteractivePreview, TheBudgetHalvesTheWidthPerDoublingOverItAndRecovers) {
    PreviewBudget budget;
    EXPECT_EQ(budget.divisor(), 1);
    budget.record(90.0, 100.0);  // within: stays
    EXPECT_EQ(budget.divisor(), 1);
    budget.record(350.0, 100.0);  // 3.5 times over: two halvings
    EXPECT_EQ(budget.divisor(), 4);
    budget.record(5000.0, 100.0);  // never below an eighth
    EXPECT_EQ(budget.divisor(), PreviewBudget::kMaxDivisor);
    budget.record(50.0, 100.0);  // between a third and the budget: stays
    EXPECT_EQ(budget.divisor(), 8);
    budget.record(20.0, 100.0);  // well under: one step back
    EXPECT_EQ(budget.divisor(), 4);
    budget.record(20.0, 100.0);
    budget.record(20.0, 100.0);
    budget.record(20.0, 100.0);
    EXPECT_EQ(budget.divisor(), 1);
}
