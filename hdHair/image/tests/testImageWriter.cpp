#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "hdHair/image/ImageWriter.h"

using namespace hdhair;
namespace fs = std::filesystem;

namespace {

class ImageWriterTest : public ::testing::Test {
protected:
    void SetUp() override {
        directory = fs::temp_directory_path() /
                    ("hdhair-image-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        fs::remove_all(directory);
        fs::create_directories(directory);
    }
    void TearDown() override { fs::remove_all(directory); }
    fs::path directory;
};

// Pre-multiplied RGBA: left pixel opaque mid grey (linear 0.214 ~ sRGB 0.5),
// right pixel red at half coverage.
Image twoPixels() {
    Image image(2, 1, 4);
    image.pixels = {0.214041f, 0.214041f, 0.214041f, 1.0f, 0.5f, 0.0f, 0.0f, 0.5f};
    return image;
}

}  // namespace

TEST_F(ImageWriterTest, ExrKeepsLinearPremultipliedHalfFloats) {
    std::string path = (directory / "out.exr").string();
    writeImage(twoPixels(), path);
    Image back = readImage(path);
    ASSERT_EQ(back.channels, 4);
    EXPECT_NEAR(back.at(0, 0, 0), 0.214041f, 1e-3f);
    EXPECT_NEAR(back.at(1, 0, 0), 0.5f, 1e-3f);
    EXPECT_NEAR(back.at(1, 0, 3), 0.5f, 1e-3f);
}

TEST_F(ImageWriterTest, PngIsSrgbEncodedWithStraightAlpha) {
    std::string path = (directory / "out.png").string();
    writeImage(twoPixels(), path);
    Image back = readImage(path);
    ASSERT_EQ(back.channels, 4);
    EXPECT_NEAR(back.at(0, 0, 0), 0.5f, 1.0f / 255.0f);   // linear 0.214 -> sRGB 0.5
    EXPECT_NEAR(back.at(1, 0, 0), 1.0f, 1.0f / 255.0f);   // un-premultiplied red
    EXPECT_NEAR(back.at(1, 0, 3), 0.5f, 1.0f / 255.0f);
}

TEST_F(ImageWriterTest, JpegHasNoAlphaAndIsOverBlack) {
    std::string path = (directory / "out.jpg").string();
    Image image(8, 8, 4);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            image.at(x, y, 0) = 0.214041f * 0.5f;  // grey at half coverage
            image.at(x, y, 3) = 0.5f;
        }
    writeImage(image, path);
    Image back = readImage(path);
    EXPECT_EQ(back.channels, 3);
    // 0.107 linear over black -> sRGB ~0.361
    EXPECT_NEAR(back.at(4, 4, 0), 0.361f, 3.0f / 255.0f);
    EXPECT_NEAR(back.at(4, 4, 1), 0.0f, 3.0f / 255.0f);
}

TEST_F(ImageWriterTest, UnsupportedExtensionAndMissingFolderAreClearErrors) {
    try {
        writeImage(twoPixels(), (directory / "out.bmpx").string());
        FAIL() << "expected an error";
    } catch (const std::runtime_error& error) {
        EXPECT_NE(std::string(error.what()).find("unsupported image extension"), std::string::npos);
    }
    try {
        writeImage(twoPixels(), (directory / "missing" / "out.png").string());
        FAIL() << "expected an error";
    } catch (const std::runtime_error& error) {
        EXPECT_NE(std::string(error.what()).find("does not exist"), std::string::npos) << error.what();
    }
}

TEST_F(ImageWriterTest, WritesAtomicallyAndLeavesNoTemporaryFiles) {
    fs::path path = directory / "out.png";
    std::ofstream(path) << "previous contents";
    writeImage(twoPixels(), path.string());
    EXPECT_EQ(readImage(path.string()).width, 2);
    int files = 0;
    for (const auto& entry : fs::directory_iterator(directory)) {
        (void)entry;
        ++files;
    }
    EXPECT_EQ(files, 1) << "the temporary file must be renamed over the target";
}
