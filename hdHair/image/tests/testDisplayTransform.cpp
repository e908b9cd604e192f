// Display transforms: known scene-linear values through each mode and each
// view of hdHair's OCIO config, against values worked out from the view's
// definition (the sRGB curve, a matrix, the ACES output transform's
// published values), and clear one-line errors for names a config lacks.

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hdHair/image/DisplayTransform.h"
#include "hdHair/image/ImageWriter.h"

using namespace hdhair;

namespace {

// The sRGB curve, IEC 61966-2-1.
double srgb(double linear) {
    return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

DisplayTransform ocio(const std::string& view, const std::string& colorSpace = "", const std::string& look = "") {
    DisplayTransformOptions options;
    options.mode = ColorCorrectionMode::OpenColorIO;
    options.config = HDHAIR_OCIO_CONFIG;
    options.view = view;
    options.colorSpace = colorSpace;
    options.look = look;
    return DisplayTransform::create(options);
}

// One grey pixel (alpha 0.5, which no transform may touch) through `transform`.
float shownGrey(const DisplayTransform& transform, float linear) {
    std::vector<float> pixel{linear, linear, linear, 0.5f};
    transform.apply(pixel.data(), 1);
    EXPECT_EQ(pixel[3], 0.5f);
    EXPECT_NEAR(pixel[0], pixel[1], 1e-5);  // grey stays grey
    EXPECT_NEAR(pixel[1], pixel[2], 1e-5);
    return pixel[0];
}

std::string errorOf(const DisplayTransformOptions& options) {
    try {
        DisplayTransform::create(options);
    } catch (const std::invalid_argument& error) {
        return error.what();
    }
    return "";
}

}  // namespace

TEST(DisplayTransform, DisabledLeavesValuesUntouched) {
    DisplayTransform disabled = DisplayTransform::create({ColorCorrectionMode::Disabled, "", "", "", "", "", kLinearRec709});
    std::vector<float> pixels{-1.0f, 0.18f, 7.5f, 0.3f, 0.0f, 1.0f, 100.0f, 1.0f};
    const std::vector<float> before = pixels;
    disabled.apply(pixels.data(), 2);
    EXPECT_EQ(pixels, before);
}

TEST(DisplayTransform, SrgbModeIsTheSrgbCurve) {
    DisplayTransform mode = DisplayTransform::create({});
    for (float value : {0.0f, 0.001f, 0.0031308f, 0.18f, 0.5f, 1.0f})
        EXPECT_NEAR(shownGrey(mode, value), srgb(value), 1e-6) << value;
}

TEST(DisplayTransform, OcioSrgbViewIsTheSrgbCurveOnLinearRec709) {
    DisplayTransform view = ocio("sRGB");
    for (float value : {0.0f, 0.05f, 0.18f, 0.5f, 1.0f}) EXPECT_NEAR(shownGrey(view, value), srgb(value), 2e-5) << value;
}

TEST(DisplayTransform, AcesCgIsBroughtToRec709PrimariesByTheAp1Matrix) {
    // AP1 to Rec.709 with Bradford adaptation, the published matrix; a
    // saturated ACEScg red shows as this Rec.709 colour, sRGB encoded.
    const double matrix[3][3] = {{1.70505099, -0.62179212, -0.08325887},
                                 {-0.13025642, 1.14080474, -0.01054832},
                                 {-0.02400336, -0.12896898, 1.15297233}};
    const double acescg[3] = {0.3, 0.1, 0.05};
    double expected[3];
    for (int row = 0; row < 3; ++row)
        expected[row] = srgb(matrix[row][0] * acescg[0] + matrix[row][1] * acescg[1] + matrix[row][2] * acescg[2]);
    DisplayTransformOptions srgbMode;
    srgbMode.colorSpace = kAcesCg;
    for (const DisplayTransform& transform : {DisplayTransform::create(srgbMode), ocio("sRGB", kAcesCg)}) {
        std::vector<float> pixel{0.3f, 0.1f, 0.05f, 1.0f};
        transform.apply(pixel.data(), 1);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(pixel[c], expected[c], 2e-4) << toString(transform.mode()) << c;
    }
}

TEST(DisplayTransform, AcesViewMatchesTheOutputTransformsPublishedValues) {
    // ACES 1.0 SDR video (sRGB): scene 1.0 shows as 0.812, and 16.29 (four
    // stops over) as 1.0 (ACES Central, "Understanding the sRGB RRT/ODT").
    DisplayTransform aces = ocio("ACES 1.0 SDR-video", kAcesCg);
    EXPECT_NEAR(shownGrey(aces, 1.0f), 0.812f, 0.001f);
    EXPECT_NEAR(shownGrey(aces, 16.292f), 1.0f, 0.001f);
    // An S-curve: mid grey lifted less than the sRGB curve lifts it, and monotonic.
    EXPECT_LT(shownGrey(aces, 0.18f), srgb(0.18));
    EXPECT_LT(shownGrey(aces, 0.1f), shownGrey(aces, 0.18f));
}

TEST(DisplayTransform, RawViewPassesValuesThrough) {
    DisplayTransform raw = ocio("Raw");
    EXPECT_FLOAT_EQ(shownGrey(raw, 0.18f), 0.18f);
    EXPECT_FLOAT_EQ(shownGrey(raw, 3.0f), 3.0f);
}

TEST(DisplayTransform, TheExposureLookDoublesTheLightBeforeTheView) {
    EXPECT_NEAR(shownGrey(ocio("sRGB", "", "Brighter"), 0.09f), srgb(0.18), 2e-5);
}

TEST(DisplayTransform, UnknownNamesAreOneLineErrorsListingTheValidOnes) {
    DisplayTransformOptions options;
    options.mode = ColorCorrectionMode::OpenColorIO;
    options.config = HDHAIR_OCIO_CONFIG;
    options.view = "Filmic";
    EXPECT_NE(errorOf(options).find("has no view 'Filmic' (views: sRGB, ACES 1.0 SDR-video, Raw)"), std::string::npos)
        << errorOf(options);
    options.view = "";
    options.display = "P3";
    EXPECT_NE(errorOf(options).find("has no display 'P3' (displays: sRGB)"), std::string::npos) << errorOf(options);
    options.display = "";
    options.look = "neon";
    EXPECT_NE(errorOf(options).find("has no look 'neon' (looks: Brighter)"), std::string::npos) << errorOf(options);
    options.look = "";
    options.colorSpace = "Rec.2020";
    EXPECT_NE(errorOf(options).find("has no colour space 'Rec.2020' (colour spaces:"), std::string::npos);
    options.config = "/nonexistent/config.ocio";
    EXPECT_NE(errorOf(options).find("cannot read the OCIO config '/nonexistent/config.ocio'"), std::string::npos);
    for (const DisplayTransformOptions& bad : {options}) EXPECT_EQ(errorOf(bad).find('\n'), std::string::npos);
}

TEST(DisplayTransform, TheConfigComesFromTheOptionThenOcioThenTheShippedOne) {
    DisplayTransformOptions options;
    options.mode = ColorCorrectionMode::OpenColorIO;
    ::unsetenv("OCIO");
    EXPECT_EQ(DisplayTransform::create(options).describe()["config"], DisplayTransform::shippedConfigPath());
    ASSERT_TRUE(std::filesystem::exists(DisplayTransform::shippedConfigPath()));
    ::setenv("OCIO", "/nonexistent/from-environment.ocio", 1);
    EXPECT_NE(errorOf(options).find("from-environment.ocio"), std::string::npos);
    options.config = HDHAIR_OCIO_CONFIG;
    EXPECT_EQ(DisplayTransform::create(options).describe()["config"], HDHAIR_OCIO_CONFIG);
    ::unsetenv("OCIO");
    nlohmann::json described = ocio("Raw", "", "Brighter").describe();
    EXPECT_EQ(described["display"], "sRGB");
    EXPECT_EQ(described["view"], "Raw");
    EXPECT_EQ(described["look"], "Brighter");
    EXPECT_EQ(described["colorSpace"], "lin_rec709");
}

TEST(DisplayTransform, DisplayImagesAreUnpremultipliedOrOverBlack) {
    // A half-covered pixel of pre-multiplied red 0.09: straight colour 0.18.
    Image linear(1, 1, 4);
    linear.pixels = {0.09f, 0.0f, 0.0f, 0.5f};
    const DisplayTransform srgbMode = DisplayTransform::create({});
    Image straight = displayImage(linear, srgbMode, false);
    EXPECT_NEAR(straight.pixels[0], srgb(0.18), 1e-6);
    EXPECT_EQ(straight.pixels[3], 0.5f);
    Image overBlack = displayImage(linear, srgbMode, true);
    EXPECT_NEAR(overBlack.pixels[0], srgb(0.09), 1e-6);
    EXPECT_EQ(overBlack.pixels[3], 1.0f);
}
