#include <stdexcept>

#include <gtest/gtest.h>

#include "hdHair/image/NearestUpscale.h"

using namespace hdhair;

TEST(NearestUpscale, RepeatsEachPixelOverTheAreaItCovers) {
    Image image(3, 2, 1);
    image.pixels = {1, 2, 3, 4, 5, 6};
    const Image large = upscaleNearest(image, 7, 4);
    ASSERT_EQ(large.width, 7);
    ASSERT_EQ(large.height, 4);
    // Columns 0-2 from x 0, 3-4 from x 1, 5-6 from x 2 (x * 3 / 7); rows 0-1
    // from y 0 and 2-3 from y 1.
    const std::vector<float> expected = {1, 1, 1, 2, 2, 3, 3, 1, 1, 1, 2, 2, 3, 3,
                                         4, 4, 4, 5, 5, 6, 6, 4, 4, 4, 5, 5, 6, 6};
    EXPECT_EQ(large.pixels, expected);
    EXPECT_EQ(upscaleNearest(image, 3, 2).pixels, image.pixels);
}

TEST(NearestUpscale, IdsAreRepeatedNeverMixed) {
    const std::vector<int32_t> ids = {5, -1};
    EXPECT_EQ(upscaleNearest(ids, 2, 1, 5, 1), (std::vector<int32_t>{5, 5, 5, -1, -1}));
    EXPECT_THROW(upscaleNearest(ids, 3, 1, 6, 1), std::invalid_argument);
    EXPECT_THROW(upscaleNearest(Image(), 4, 4), std::invalid_argument);
}
