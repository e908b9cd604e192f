#include <stdexcept>

#include <gtest/gtest.h>

#include "hdHair/image/BoxDownsample.h"

using namespace hdhair;

TEST(BoxDownsample, AveragesEachBlockPerChannel) {
    Image image(4, 2, 2);
    // Left block: alpha covered in 1 of 4 samples; right block: all 4.
    image.at(0, 0, 1) = 1.0f;
    image.at(0, 0, 0) = 0.5f;
    for (int y = 0; y < 2; ++y)
        for (int x = 2; x < 4; ++x) {
            image.at(x, y, 0) = float(x + y);
            image.at(x, y, 1) = 1.0f;
        }
    Image small = boxDownsample(image, 2);
    ASSERT_EQ(small.width, 2);
    ASSERT_EQ(small.height, 1);
    EXPECT_FLOAT_EQ(small.at(0, 0, 0), 0.125f);
    EXPECT_FLOAT_EQ(small.at(0, 0, 1), 0.25f);
    EXPECT_FLOAT_EQ(small.at(1, 0, 0), (2.0f + 3.0f + 3.0f + 4.0f) / 4.0f);
    EXPECT_FLOAT_EQ(small.at(1, 0, 1), 1.0f);
}

TEST(BoxDownsample, FactorOneKeepsTheImageAndBadFactorsThrow) {
    Image image(3, 3, 1, 0.25f);
    EXPECT_EQ(boxDownsample(image, 1).pixels, image.pixels);
    EXPECT_THROW(boxDownsample(image, 2), std::invalid_argument);
    EXPECT_THROW(boxDownsample(image, 0), std::invalid_argument);
}
