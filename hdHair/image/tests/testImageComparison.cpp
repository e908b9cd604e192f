#include <cmath>

#include <gtest/gtest.h>

#include "hdHair/image/ImageComparison.h"

using namespace hdhair;

TEST(ImageComparison, IdenticalImagesAreWithinAnyTolerance) {
    Image a(4, 4, 4, 0.25f);
    ImageDifference d = compareImages(a, a, 0.0);
    EXPECT_EQ(d.maxDifference, 0.0);
    EXPECT_TRUE(withinTolerance(d, ImageTolerance{}));
}

TEST(ImageComparison, CountsPixelsOverTheThreshold) {
    Image a(10, 10, 4, 0.0f), b(10, 10, 4, 0.0f);
    b.at(3, 3, 1) = 0.5f;
    ImageDifference d = compareImages(a, b, 0.1);
    EXPECT_DOUBLE_EQ(d.fractionOverThreshold, 0.01);
    EXPECT_DOUBLE_EQ(d.maxDifference, 0.5);
    EXPECT_FALSE(withinTolerance(d, ImageTolerance{0.1, 0.005, 1.0}));
    EXPECT_TRUE(withinTolerance(d, ImageTolerance{0.1, 0.02, 1.0}));
    EXPECT_FALSE(withinTolerance(d, ImageTolerance{0.1, 0.02, 0.4}));
}

TEST(ImageComparison, SizeMismatchAndNaNFail) {
    EXPECT_FALSE(withinTolerance(compareImages(Image(2, 2, 4), Image(3, 2, 4), 0.1), ImageTolerance{}));
    Image a(2, 2, 4), b(2, 2, 4);
    a.at(0, 0, 0) = NAN;
    EXPECT_FALSE(withinTolerance(compareImages(a, b, 0.1), ImageTolerance{0.1, 1.0, 1.0}));
}
