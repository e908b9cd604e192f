// Built and run only with OpenUSD. In Hydra hosts the delegate's colour AOV
// stays scene-linear, so the host's colour correction applies once, never
// twice: usdrecord --renderer HdHair through its GL path (under Xvfb, with
// its default sRGB correction) must show what hdhair-record
// --colorCorrectionMode sRGB shows.
//
// usdrecord writes the corrected pre-multiplied colour with alpha, while
// hdhair-record's PNG holds straight colour (PNG's convention): the test
// brings hdhair-record's pixels to usdrecord's form (decode, multiply by
// alpha, encode) and compares over covered pixels within 1.5/255 (Hydra's
// half-float colour buffer and two 8-bit roundings). Correcting twice, or
// not at all, moves mid-tones by tens of steps and fails (checked below).

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "Commands.h"
#include "hdHair/image/ImageComparison.h"
#include "hdHair/image/ImageWriter.h"

using namespace hdhair;
namespace fs = std::filesystem;

namespace {

double srgbDecode(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }
double srgbEncode(double l) { return l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055; }

// hdhair-record's straight-alpha sRGB pixels as a host's corrected
// pre-multiplied colour; `times` sRGB encodings of the linear colour.
Image asHostWrites(const Image& straight, int times) {
    Image host = straight;
    for (size_t p = 0; p < host.pixels.size(); p += 4) {
        const double alpha = straight.pixels[p + 3];
        for (size_t c = 0; c < 3; ++c) {
            double value = srgbDecode(straight.pixels[p + c]) * alpha;
            for (int i = 0; i < times; ++i) value = srgbEncode(value);
            host.pixels[p + c] = float(value);
        }
    }
    return host;
}

}  // namespace

TEST(HostColorCorrection, UsdrecordCorrectsTheLinearAovOnce) {
    const fs::path directory = fs::temp_directory_path() / ("hdhair-host-color-" + std::to_string(::getpid()));
    fs::create_directories(directory);
    const std::string stage = std::string(HDHAIR_SOURCE_DIR) + "/examples/wavy_strands.usda";
    const std::string hosted = (directory / "usdrecord.png").string(), ours = (directory / "hdhair.png").string();
    std::string log;
    ASSERT_EQ(testenv::runCommand("HOME=" + directory.string() + " PYTHONPATH=" + HDHAIR_PXR_PYTHONPATH +
                                      " PXR_PLUGINPATH_NAME=" + HDHAIR_PLUGIN_RESOURCES + " timeout 300 xvfb-run -a " +
                                      HDHAIR_PXR_BIN + "/usdrecord --renderer HdHair --camera /World/main_cam "
                                      "--imageWidth 160 " + stage + " " + hosted,
                                  &log),
              0)
        << log;
    ASSERT_EQ(testenv::runCommand(std::string(HDHAIR_RECORD) + " --reader embedded --colorCorrectionMode sRGB "
                                  "--camera /World/main_cam --imageWidth 160 " + stage + " " + ours,
                                  &log),
              0)
        << log;
    const Image host = readImage(hosted), straight = readImage(ours);
    const CoveredPixelTolerance tolerance = exactWithin(1.5 / 255.0);
    const ImageComparison once = compareImages(host, asHostWrites(straight, 1), tolerance);
    EXPECT_TRUE(once.passed) << once.description;
    EXPECT_GT(once.coveredPixels, 2000u);
    // The comparison tells the mistakes apart: corrected twice, or never.
    EXPECT_FALSE(compareImages(host, asHostWrites(straight, 2), tolerance).passed);
    EXPECT_FALSE(compareImages(host, asHostWrites(straight, 0), tolerance).passed);
    fs::remove_all(directory);
}
