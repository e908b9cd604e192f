#include <stdexcept>

#include <gtest/gtest.h>

#include "hdHair/base/FrameSpec.h"

using namespace hdhair;

TEST(FrameSpec, FramesRangesAndStrides) {
    EXPECT_EQ(parseFrameSpec("12"), (std::vector<double>{12}));
    EXPECT_EQ(parseFrameSpec("1:4"), (std::vector<double>{1, 2, 3, 4}));
    EXPECT_EQ(parseFrameSpec("1:6x2"), (std::vector<double>{1, 3, 5}));
    EXPECT_EQ(parseFrameSpec("0:1x0.25,7"), (std::vector<double>{0, 0.25, 0.5, 0.75, 1, 7}));
    std::vector<double> tenths = parseFrameSpec("0:1x0.1");
    ASSERT_EQ(tenths.size(), 11u);
    EXPECT_NEAR(tenths.back(), 1.0, 1e-12);
}

TEST(FrameSpec, BadSpecsAreOneLineErrors) {
    EXPECT_THROW(parseFrameSpec(""), std::invalid_argument);
    EXPECT_THROW(parseFrameSpec("a:3"), std::invalid_argument);
    EXPECT_THROW(parseFrameSpec("5:1"), std::invalid_argument);
    EXPECT_THROW(parseFrameSpec("1:5x0"), std::invalid_argument);
    EXPECT_THROW(parseFrameSpec("1:5x-1"), std::invalid_argument);
    EXPECT_THROW(parseFrameSpec("0:1e9"), std::invalid_argument);
    EXPECT_THROW(parseFrameSpec("nan"), std::invalid_argument);
}

TEST(FrameSpec, PlaceholdersArePaddedLikeUsdrecord) {
    EXPECT_EQ(expandFramePlaceholder("out.####.png", 7), "out.0007.png");
    EXPECT_EQ(expandFramePlaceholder("out.#.exr", 12), "out.12.exr");
    EXPECT_EQ(expandFramePlaceholder("out.###.##.png", 1.5), "out.001.50.png");
    EXPECT_EQ(expandFramePlaceholder("still.png", 3), "still.png");
    EXPECT_THROW(expandFramePlaceholder("out.####.png", 1.5), std::invalid_argument);
    EXPECT_TRUE(hasFramePlaceholder("a#.png"));
    EXPECT_FALSE(hasFramePlaceholder("a.png"));
}

// hdhair-farm prints the frames to resubmit with formatFrameSpec: the spec
// must read back as the same frames.
TEST(FrameSpec, FormattedSpecsReadBackAsTheSameFrames) {
    EXPECT_EQ(formatFrameSpec({7}), "7");
    EXPECT_EQ(formatFrameSpec({1, 2, 3, 4, 9, 12.5, 13, 14}), "1:4,9,12.5,13:14");
    EXPECT_EQ(formatFrameSpec({}), "");
    EXPECT_EQ(formatFrameSpec({123456.5, 1000000, 1000001}), "123456.5,1000000:1000001");
    for (const std::vector<double>& frames :
         {std::vector<double>{3, 1, 2}, std::vector<double>{-2, -1, 0, 1}, std::vector<double>{1.5, 2.5, 3.5}})
        EXPECT_EQ(parseFrameSpec(formatFrameSpec(frames)), frames);
}
