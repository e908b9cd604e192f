#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <numeric>
#include <string>

#include <glm/gtc/constants.hpp>

#include "hdHair/base/InputError.h"
#include "hdHair/environment/LatlongTexture.h"
#include "hdHair/environment/tests/LatlongTestTextures.h"

using namespace hdhair;
using hdhair::test::TemporaryFolder;
using hdhair::test::writeTestImage;

namespace {

// The message of the InputError readLatlongTexture throws ("" if none).
std::string refusal(const std::string& path) {
    try {
        readLatlongTexture(path, 64, 32);
    } catch (const InputError& error) {
        return error.what();
    }
    return std::string();
}

}  // namespace

TEST(RadianceGrid, CellsCoverTheSphereOnce) {
    const RadianceGrid grid = latlongGrid(64, 32);
    ASSERT_EQ(grid.cellCount(), 64u * 32u);
    const double total = std::accumulate(grid.solidAngles.begin(), grid.solidAngles.end(), 0.0);
    EXPECT_NEAR(total, 4.0 * glm::pi<double>(), 1e-4);
    // Row 0 of a 2-row grid is the upper hemisphere: 2π / width each.
    EXPECT_NEAR(latlongCellSolidAngle(0, 4, 2), glm::two_pi<float>() / 4.0f, 1e-6f);
}

// Each cell is the solid-angle weighted mean of its texels, by hand: in an
// 8 × 4 image on a 4 × 2 grid, cell row 0 holds texel rows 0 and 1, whose
// solid angles are in the ratio (1 − cos 45°) : (cos 45° − cos 90°) =
// 0.29289 : 0.70711.
TEST(LatlongTexture, CellsAreSolidAngleWeightedMeans) {
    TemporaryFolder folder;
    std::vector<float> pixels;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x) pixels.insert(pixels.end(), {float(y + 1), float(x), 0.5f});
    const std::string path = folder.path("steps.exr");
    writeTestImage(path, 8, 4, 3, pixels);
    const LatlongTextureRead read = readLatlongTexture(path, 4, 2);
    EXPECT_EQ(read.imageWidth, 8);
    EXPECT_EQ(read.imageHeight, 4);
    EXPECT_EQ(read.repairedTexels, 0u);
    EXPECT_FALSE(read.srgbDecoded);
    ASSERT_EQ(read.grid.width, 4);
    ASSERT_EQ(read.grid.height, 2);
    EXPECT_NEAR(read.grid.radiance[0].r, 0.29289f * 1.0f + 0.70711f * 2.0f, 1e-5f);
    EXPECT_NEAR(read.grid.radiance[4].r, 0.70711f * 3.0f + 0.29289f * 4.0f, 1e-5f);  // mirrored below the horizon
    EXPECT_NEAR(read.grid.radiance[1].g, 2.5f, 1e-5f);  // texel columns 2 and 3
    EXPECT_NEAR(read.grid.radiance[7].b, 0.5f, 1e-6f);
    // A grid larger than the image is the image's size.
    EXPECT_EQ(readLatlongTexture(path, 64, 32).grid.width, 8);
}

TEST(LatlongTexture, TiledFilesReadAsScanlineFilesDo) {
    TemporaryFolder folder;
    const std::vector<float> pixels = test::latlongPixels(96, 48, [](const glm::vec3& d) {
        return glm::vec3(1.0f + d.x, 1.0f + d.y, 1.0f + d.z);
    });
    writeTestImage(folder.path("lines.exr"), 96, 48, 3, pixels);
    writeTestImage(folder.path("tiles.exr"), 96, 48, 3, pixels, OIIO::TypeDesc::HALF, 32);
    const RadianceGrid lines = readLatlongTexture(folder.path("lines.exr"), 16, 8).grid;
    const RadianceGrid tiles = readLatlongTexture(folder.path("tiles.exr"), 16, 8).grid;
    for (size_t cell = 0; cell < lines.cellCount(); ++cell) {
        EXPECT_NEAR(tiles.radiance[cell].r, lines.radiance[cell].r, 2e-3f) << cell;  // half precision
        EXPECT_NEAR(tiles.radiance[cell].b, lines.radiance[cell].b, 2e-3f) << cell;
    }
}

// 8-bit RGB is sRGB-encoded, as Storm's automatic colour space takes it; a
// one-channel image is grey.
TEST(LatlongTexture, EightBitIsSrgbAndOneChannelIsGrey) {
    TemporaryFolder folder;
    writeTestImage(folder.path("srgb.png"), 4, 2, 3, std::vector<float>(24, 128.0f / 255.0f), OIIO::TypeDesc::UINT8);
    const LatlongTextureRead srgb = readLatlongTexture(folder.path("srgb.png"), 4, 2);
    EXPECT_TRUE(srgb.srgbDecoded);
    EXPECT_NEAR(srgb.grid.radiance[0].g, 0.2158605f, 1e-5f);  // ((128/255 + 0.055) / 1.055)^2.4
    writeTestImage(folder.path("grey.exr"), 4, 2, 1, std::vector<float>(8, 0.75f));
    const LatlongTextureRead grey = readLatlongTexture(folder.path("grey.exr"), 4, 2);
    EXPECT_FALSE(grey.srgbDecoded);
    EXPECT_EQ(grey.grid.radiance[5], glm::vec3(0.75f));
}

// NaN, infinite and negative channels read as 0, and are counted.
TEST(LatlongTexture, NonFiniteAndNegativeTexelsReadAsZero) {
    TemporaryFolder folder;
    std::vector<float> pixels(4 * 2 * 3, 1.0f);
    pixels[0] = std::numeric_limits<float>::quiet_NaN();   // texel (0, 0) red
    pixels[4] = std::numeric_limits<float>::infinity();    // texel (1, 0) green
    pixels[8] = -2.0f;                                     // texel (2, 0) blue
    pixels[9] = -std::numeric_limits<float>::infinity();   // texel (3, 0) red
    const std::string path = folder.path("bad.exr");
    writeTestImage(path, 4, 2, 3, pixels);
    const LatlongTextureRead read = readLatlongTexture(path, 4, 2);
    EXPECT_EQ(read.repairedTexels, 4u);
    EXPECT_EQ(read.grid.radiance[0], glm::vec3(0, 1, 1));
    EXPECT_EQ(read.grid.radiance[1], glm::vec3(1, 0, 1));
    EXPECT_EQ(read.grid.radiance[2], glm::vec3(1, 1, 0));
    EXPECT_EQ(read.grid.radiance[3], glm::vec3(0, 1, 1));
    EXPECT_EQ(read.grid.radiance[4], glm::vec3(1, 1, 1));
}

// A header that declares a huge image is refused before any texel is read;
// so are files that are not images, not there, or not files.
TEST(LatlongTexture, UnusableFilesAreRefusedNamingTheFile) {
    TemporaryFolder folder;
    const std::string huge = folder.path("huge.hdr");
    std::ofstream(huge, std::ios::binary) << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 100000 +X 200000\n";
    const std::string hugeRefusal = refusal(huge);
    EXPECT_NE(hugeRefusal.find("'" + huge + "'"), std::string::npos) << hugeRefusal;
    EXPECT_NE(hugeRefusal.find("200000 × 100000"), std::string::npos) << hugeRefusal;

    const std::string garbage = folder.path("garbage.exr");
    std::ofstream(garbage, std::ios::binary) << "not an image";
    EXPECT_NE(refusal(garbage).find("cannot read '" + garbage + "'"), std::string::npos);
    EXPECT_NE(refusal(folder.path("missing.exr")).find("No such file"), std::string::npos);
    EXPECT_NE(refusal(folder.path("")).find("a directory"), std::string::npos);
}
