// Built and run only with OpenUSD: a textured DomeLight lights a grey sphere
// from the same side in hdHair as in Storm (usdrecord --renderer GL, under
// Xvfb), and turning the dome about +Y turns its light the same way in both
// (the convention is hdHair/environment/LatlongDirections.h).
//
// The dome is red over its +X half and blue over its -X half (a latlong map
// whose left half, u < 1/2, is +X). The camera looks down -Z from +Z, so the
// sphere's +X side is the image's right. Unturned, the right of the sphere
// is red and its left blue; turned +90° about +Y the dome's -X half faces
// the camera (its +X half goes behind the sphere), so the sphere's centre is
// blue; turned -90° it is red. A flipped u, v or handedness swaps one of
// these in one renderer and not the other.

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "Commands.h"
#include "hdHair/image/ImageWriter.h"

namespace fs = std::filesystem;
using hdhair::Image;
using hdhair::readImage;
using hdhair::testenv::runCommand;
using hdhair::testenv::shellQuoted;

namespace {

constexpr int kWidth = 96;  // 96 × 70 with the camera's apertures

// A latlong map, red where u < 1/2 (the dome's +X half), blue elsewhere.
void writeHalfRedHalfBlueDome(const std::string& path) {
    const int width = 64, height = 32;
    std::vector<float> pixels(size_t(width) * height * 3);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            float* texel = &pixels[(size_t(y) * width + x) * 3];
            const bool plusX = x < width / 2;
            texel[0] = plusX ? 1.0f : 0.02f;
            texel[1] = 0.02f;
            texel[2] = plusX ? 0.02f : 1.0f;
        }
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out);
    ASSERT_TRUE(out->open(path, OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::HALF)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
    ASSERT_TRUE(out->close());
}

// A UV sphere of radius 1 at the origin (quads, triangles at the poles),
// a camera 8 units out on +Z, and the dome turned `turnDegrees` about +Y.
std::string sphereUnderDome(double turnDegrees) {
    const int rings = 16, segments = 32;
    const double pi = 3.14159265358979323846;
    std::string points, counts, indices;
    auto point = [&](double theta, double phi) {
        points += "(" + std::to_string(std::sin(theta) * std::sin(phi)) + ", " + std::to_string(std::cos(theta)) +
                  ", " + std::to_string(std::sin(theta) * std::cos(phi)) + "), ";
    };
    point(0.0, 0.0);  // 0: the north pole
    for (int r = 1; r < rings; ++r)
        for (int s = 0; s < segments; ++s) point(pi * r / rings, 2.0 * pi * s / segments);
    point(pi, 0.0);  // the south pole
    const int south = 1 + (rings - 1) * segments;
    auto at = [&](int ring, int s) { return 1 + (ring - 1) * segments + (s % segments); };
    for (int s = 0; s < segments; ++s) {  // wound counter-clockwise seen from outside
        counts += "3, ";
        indices += "0, " + std::to_string(at(1, s)) + ", " + std::to_string(at(1, s + 1)) + ", ";
    }
    for (int r = 1; r + 1 < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            counts += "4, ";
            indices += std::to_string(at(r, s)) + ", " + std::to_string(at(r + 1, s)) + ", " +
                       std::to_string(at(r + 1, s + 1)) + ", " + std::to_string(at(r, s + 1)) + ", ";
        }
    for (int s = 0; s < segments; ++s) {
        counts += "3, ";
        indices += std::to_string(at(rings - 1, s)) + ", " + std::to_string(south) + ", " +
                   std::to_string(at(rings - 1, s + 1)) + ", ";
    }
    return "#usda 1.0\n(\n    upAxis = \"Y\"\n)\n\n"
           "def Camera \"cam\"\n{\n    float focalLength = 50\n    float horizontalAperture = 20.955\n"
           "    float verticalAperture = 15.2908\n    float2 clippingRange = (1, 100)\n"
           "    double3 xformOp:translate = (0, 0, 8)\n    uniform token[] xformOpOrder = [\"xformOp:translate\"]\n}\n\n"
           "def Mesh \"sphere\"\n{\n    int[] faceVertexCounts = [" + counts + "]\n    int[] faceVertexIndices = [" +
           indices + "]\n    point3f[] points = [" + points + "]\n    uniform token subdivisionScheme = \"none\"\n"
           "    color3f[] primvars:displayColor = [(0.5, 0.5, 0.5)]\n}\n\n"
           "def DomeLight \"dome\"\n{\n    float inputs:intensity = 0.5\n    asset inputs:texture:file = @./dome.exr@\n"
           "    token inputs:texture:format = \"latlong\"\n    float xformOp:rotateY = " + std::to_string(turnDegrees) +
           "\n    uniform token[] xformOpOrder = [\"xformOp:rotateY\"]\n}\n";
}

struct RegionColour {
    double red = 0.0, blue = 0.0;
};

// The mean red and blue of a square of the image, its centre at (cx, cy)
// in units of the image's width (y down), 5 % of the width across.
RegionColour regionColour(const Image& image, double cx, double cy) {
    RegionColour colour;
    const int half = std::max(1, int(0.025 * image.width));
    const int x0 = int(cx * image.width), y0 = int(cy * image.width);
    int n = 0;
    for (int y = y0 - half; y <= y0 + half; ++y)
        for (int x = x0 - half; x <= x0 + half; ++x) {
            colour.red += image.at(x, y, 0);
            colour.blue += image.at(x, y, 2);
            ++n;
        }
    colour.red /= n;
    colour.blue /= n;
    return colour;
}

class DomeOrientation : public ::testing::Test {
protected:
    void SetUp() override {
        folder_ = fs::temp_directory_path() / ("hdhair-dome-storm-" + std::to_string(::getpid()));
        fs::create_directories(folder_);
        writeHalfRedHalfBlueDome((folder_ / "dome.exr").string());
    }
    void TearDown() override { fs::remove_all(folder_); }

    // The stage turned `turnDegrees`, rendered by `renderer` ("storm",
    // "plugin" or "embedded"), read back.
    Image render(const std::string& renderer, double turnDegrees) {
        const std::string name = renderer + std::to_string(int(turnDegrees));
        const std::string stage = (folder_ / (name + ".usda")).string(), image = (folder_ / (name + ".png")).string();
        std::ofstream(stage) << sphereUnderDome(turnDegrees);
        const std::string usd = "PYTHONPATH=" + shellQuoted(HDHAIR_PXR_PYTHONPATH) + " PXR_PLUGINPATH_NAME=" +
                                shellQuoted(HDHAIR_PLUGIN_RESOURCES) + " ";
        const std::string frame = " --camera /cam --imageWidth " + std::to_string(kWidth) + " " + shellQuoted(stage) +
                                  " " + shellQuoted(image);
        std::string command;
        if (renderer == "storm")
            command = usd + "timeout 300 xvfb-run -a " + shellQuoted(std::string(HDHAIR_PXR_BIN) + "/usdrecord") +
                      " --renderer GL --disableCameraLight" + frame;
        else if (renderer == "plugin")
            command = usd + shellQuoted(std::string(HDHAIR_PXR_BIN) + "/usdrecord") +
                      " --renderer HdHair --disableGpu --disableCameraLight" + frame;
        else
            command = shellQuoted(HDHAIR_RECORD) + " --reader embedded" + frame;
        std::string output;
        EXPECT_EQ(runCommand(command, &output), 0) << command << "\n" << output;
        return readImage(image);
    }

    fs::path folder_;
};

// The sphere's right and left sides (image x 0.5 ± 0.2 of the width, on its
// equator: the sphere's radius is 0.3 of the width, so normals there lean
// about 40° towards ±X) and its centre.
// A side is "lit red" when its display red is at least 1.1 times its blue:
// the images are display-encoded (sRGB), which compresses ratios, and
// Storm's preview surface adds specular; a flipped convention gives a ratio
// below 1. usdrecord's camera light is off (--disableCameraLight).
constexpr double kDominant = 1.1;
constexpr double kRight = 0.70, kLeft = 0.30, kCentre = 0.5, kEquator = 70.0 / 96.0 / 2.0;

TEST_F(DomeOrientation, TheDomesRedHalfLightsTheSameSideAsInStorm) {
    for (const char* renderer : {"storm", "plugin", "embedded"}) {
        const Image image = render(renderer, 0.0);
        const RegionColour right = regionColour(image, kRight, kEquator), left = regionColour(image, kLeft, kEquator);
        EXPECT_GT(right.red, kDominant * right.blue) << renderer << ": the sphere's +X side is lit by the dome's +X half";
        EXPECT_GT(left.blue, kDominant * left.red) << renderer << ": the sphere's -X side is lit by the dome's -X half";
    }
}

TEST_F(DomeOrientation, TurningTheDomeAboutYTurnsItsLightAsInStorm) {
    for (const char* renderer : {"storm", "plugin", "embedded"}) {
        const RegionColour plus = regionColour(render(renderer, 90.0), kCentre, kEquator);
        const RegionColour minus = regionColour(render(renderer, -90.0), kCentre, kEquator);
        EXPECT_GT(plus.blue, kDominant * plus.red) << renderer << ": +90° about +Y brings the dome's -X half to +Z";
        EXPECT_GT(minus.red, kDominant * minus.blue) << renderer << ": -90° about +Y brings the dome's +X half to +Z";
    }
}

}  // namespace
