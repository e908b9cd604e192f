#include <cmath>

#include <gtest/gtest.h>

#include "hdHair/image/ImageComparison.h"

using namespace hdhair;

namespace {

// A 100x100 frame, transparent black but for an opaque 10x10 patch of `shade`
// at (20..29, 40..49): 100 covered pixels in 10,000.
Image patchImage(float shade) {
    Image image(100, 100, 4, 0.0f);
    for (int y = 40; y < 50; ++y)
        for (int x = 20; x < 30; ++x) {
            for (int c = 0; c < 3; ++c) image.at(x, y, c) = shade;
            image.at(x, y, 3) = 1.0f;
        }
    return image;
}

const CoveredPixelTolerance kTolerance{0.02, 0.05, 0.25, 2};

}  // namespace

TEST(ImageComparison, IdenticalImagesPassWithNoDifference) {
    Image image = patchImage(0.5f);
    ImageComparison c = compareImages(image, image, exactWithin(0.0));
    EXPECT_TRUE(c.passed) << c.description;
    EXPECT_EQ(c.coveredPixels, 100u);
    EXPECT_EQ(c.maxDifference, 0.0);
    EXPECT_EQ(c.worstChannel, -1);
    EXPECT_NE(c.description.find("no covered pixel differs"), std::string::npos) << c.description;
}

TEST(ImageComparison, AChangedShadeFailsHoweverMuchBackgroundSurroundsIt) {
    // 1 % of the frame, all of what is covered: over the whole frame this
    // would be within a 5 % share.
    ImageComparison c = compareImages(patchImage(0.45f), patchImage(0.5f), kTolerance);
    EXPECT_FALSE(c.passed);
    EXPECT_EQ(c.coveredPixels, 100u);
    EXPECT_EQ(c.pixelsOverThreshold, 100u);
    EXPECT_DOUBLE_EQ(c.shareOverThreshold, 1.0);
    EXPECT_EQ(c.outliers, 0u);
    EXPECT_NEAR(c.meanDifference, 0.05 * 3.0 / 4.0, 1e-6);  // three colour channels of four differ
    EXPECT_NE(c.description.find("OUT OF TOLERANCE: 100 of 100 covered pixels (100.000%) differ by 0.0200 to 0.2500 "
                                 "(allowed 5.000%), 0 by more (allowed 2)"),
              std::string::npos)
        << c.description;
}

TEST(ImageComparison, BackgroundColourUnderZeroAlphaIsNotCompared) {
    // A straight-alpha PNG may hold any colour where alpha is 0.
    Image a = patchImage(0.5f), b = patchImage(0.5f);
    for (int x = 60; x < 90; ++x) a.at(x, 5, 0) = 1.0f;
    b.at(0, 0, 1) = 0.7f;
    ImageComparison c = compareImages(a, b, exactWithin(0.0));
    EXPECT_TRUE(c.passed) << c.description;
    EXPECT_EQ(c.coveredPixels, 100u);
}

TEST(ImageComparison, APixelCoveredInEitherImageIsCompared) {
    Image a = patchImage(0.5f), b = patchImage(0.5f);
    a.at(70, 70, 3) = 0.5f;  // a strand where the baseline has none
    a.at(70, 70, 0) = 0.5f;
    b.at(20, 40, 3) = 0.0f;  // the baseline's strand missing from the render
    ImageComparison c = compareImages(a, b, kTolerance);
    EXPECT_EQ(c.coveredPixels, 101u);
    EXPECT_EQ(c.pixelsOverThreshold, 0u);
    EXPECT_EQ(c.outliers, 2u);
    EXPECT_TRUE(c.passed) << "two outliers are allowed: " << c.description;
}

TEST(ImageComparison, OutliersBeyondTheAllowedCountFailAndTheWorstIsNamed) {
    Image a = patchImage(0.5f), b = patchImage(0.5f);
    a.at(21, 41, 1) = 0.9f;
    a.at(22, 41, 1) = 0.8f;
    EXPECT_TRUE(compareImages(a, b, kTolerance).passed) << "two edge pixels a pixel apart";
    a.at(27, 48, 2) = 1.0f;  // the largest difference: 0.5
    ImageComparison c = compareImages(a, b, kTolerance);
    EXPECT_FALSE(c.passed);
    EXPECT_EQ(c.outliers, 3u);
    EXPECT_EQ(c.pixelsOverThreshold, 0u) << "outliers are counted apart from shade differences";
    EXPECT_EQ(c.worstX, 27);
    EXPECT_EQ(c.worstY, 48);
    EXPECT_EQ(c.worstChannel, 2);
    EXPECT_DOUBLE_EQ(c.maxDifference, 0.5);
    EXPECT_NE(c.description.find("worst (27, 48) channel 2: 1.0000 vs 0.5000 expected"), std::string::npos)
        << c.description;
}

TEST(ImageComparison, ShadeDifferencesAreAllowedUpToTheirShareOfCoveredPixels) {
    Image a = patchImage(0.5f), b = patchImage(0.5f);
    // Five of 100 covered pixels 0.03 apart: exactly the 5 % allowed.
    for (int x = 20; x < 25; ++x) a.at(x, 40, 0) = 0.53f;
    ImageComparison atLimit = compareImages(a, b, kTolerance);
    EXPECT_TRUE(atLimit.passed) << atLimit.description;
    EXPECT_EQ(atLimit.pixelsOverThreshold, 5u);
    EXPECT_EQ(atLimit.outliers, 0u);
    a.at(25, 40, 0) = 0.53f;
    ImageComparison overLimit = compareImages(a, b, kTolerance);
    EXPECT_FALSE(overLimit.passed) << overLimit.description;
    EXPECT_EQ(overLimit.pixelsOverThreshold, 6u);
    // Differences at or below the threshold never count.
    Image c = patchImage(0.515f);
    EXPECT_EQ(compareImages(c, b, kTolerance).pixelsOverThreshold, 0u);
}

TEST(ImageComparison, NonFiniteValuesAreOutliers) {
    Image a = patchImage(0.5f), b = patchImage(0.5f);
    a.at(23, 44, 0) = NAN;
    ImageComparison c = compareImages(a, b, CoveredPixelTolerance{0.1, 1.0, 1.0, 0});
    EXPECT_FALSE(c.passed);
    EXPECT_EQ(c.outliers, 1u);
    EXPECT_EQ(c.worstX, 23);
    EXPECT_EQ(c.worstY, 44);
    Image d = patchImage(0.5f);
    d.at(80, 80, 3) = INFINITY;  // a non-finite alpha is covered, and different
    EXPECT_FALSE(compareImages(d, b, CoveredPixelTolerance{0.1, 1.0, 1.0, 0}).passed);
}

TEST(ImageComparison, ImagesWithoutAlphaCompareEveryPixel) {
    Image a(10, 10, 3, 0.0f), b(10, 10, 3, 0.0f);
    a.at(9, 9, 2) = 0.5f;
    ImageComparison c = compareImages(a, b, exactWithin(0.1));
    EXPECT_EQ(c.coveredPixels, 100u);
    EXPECT_EQ(c.outliers, 1u);
    EXPECT_FALSE(c.passed);
}

TEST(ImageComparison, DifferentSizesFail) {
    ImageComparison c = compareImages(Image(2, 2, 4), Image(3, 2, 4), CoveredPixelTolerance{1.0, 1.0, 1.0, 100});
    EXPECT_FALSE(c.passed);
    EXPECT_FALSE(c.sizesMatch);
    EXPECT_NE(c.description.find("2x2x4 vs 3x2x4"), std::string::npos) << c.description;
    EXPECT_FALSE(compareImages(Image(2, 2, 4), Image(2, 2, 3), CoveredPixelTolerance{1.0, 1.0, 1.0, 100}).passed);
}

// Block errors: zero-mean per-pixel noise (a checkerboard of +-0.2 about the
// reference) vanishes over 2x2 blocks, while a bias (10 % too bright) keeps
// its size at every block; the last partial blocks are left out.
TEST(ImageComparison, BlockErrorAveragesNoiseAndKeepsBias) {
    Image reference(64, 64, 4, 0.5f), noisy(64, 64, 4, 0.5f), biased(64, 64, 4, 0.55f);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            for (int c = 0; c < 3; ++c) noisy.at(x, y, c) = (x + y) % 2 ? 0.7f : 0.3f;
            reference.at(x, y, 3) = noisy.at(x, y, 3) = biased.at(x, y, 3) = 1.0f;
        }
    EXPECT_NEAR(blockRelativeColorError(noisy, reference, 1).rootMeanSquare, 0.4, 1e-6);
    EXPECT_NEAR(blockRelativeColorError(noisy, reference, 2).rootMeanSquare, 0.0, 1e-6);
    EXPECT_EQ(blockRelativeColorError(noisy, reference, 2).coveredPixels, 32u * 32u);
    EXPECT_NEAR(blockRelativeColorError(biased, reference, 1).rootMeanSquare, 0.1, 1e-6);
    EXPECT_NEAR(blockRelativeColorError(biased, reference, 8).rootMeanSquare, 0.1, 1e-6);
    EXPECT_NEAR(blockRelativeColorError(biased, reference, 8).sumRatio, 1.1, 1e-6);

    Image edge = reference;
    edge.at(63, 63, 0) = 5.0f;  // in the last partial block of 6x6 blocks (60 = 10 x 6)
    EXPECT_EQ(blockRelativeColorError(edge, reference, 6).rootMeanSquare, 0.0);
    EXPECT_GT(blockRelativeColorError(edge, reference, 8).rootMeanSquare, 0.0);
    EXPECT_THROW(blockRelativeColorError(edge, reference, 0), std::invalid_argument);
    EXPECT_THROW(blockRelativeColorError(edge, Image(32, 32, 4), 2), std::invalid_argument);
}
