#include <stdexcept>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hdHair/render/RenderSettings.h"

using namespace hdhair;

namespace {

std::string errorOf(RenderSettings& settings, const std::string& assignment) {
    try {
        settings.setFromAssignment(assignment);
    } catch (const std::invalid_argument& error) {
        return error.what();
    }
    return "";
}

}  // namespace

TEST(RenderSettings, DefaultsComeFromTheDescriptors) {
    RenderSettings settings;
    EXPECT_DOUBLE_EQ(settings.getFloat("kajiyaKay:specular"), 0.35);
    EXPECT_EQ(settings.getToken("cameraLight"), "auto");
    EXPECT_EQ(settings.getInt("interactiveBudgetMs"), 100);
    for (const SettingDescriptor& descriptor : RenderSettings::descriptors())
        EXPECT_TRUE(settings.toJson().contains(descriptor.name)) << descriptor.name;
}

TEST(RenderSettings, ComplexityScalesTessellationUnlessSetExplicitly) {
    RenderSettings settings;
    EXPECT_EQ(settings.getInt("maxSegmentsPerSpan"), 8);
    settings.setComplexity(Complexity::VeryHigh);
    EXPECT_EQ(settings.getInt("maxSegmentsPerSpan"), 64);
    EXPECT_DOUBLE_EQ(settings.getFloat("pixelsPerSegment"), 1.0);
    EXPECT_DOUBLE_EQ(settings.getFloat("tessellationTolerance"), 0.015);
    settings.setComplexity(Complexity::Medium);
    EXPECT_DOUBLE_EQ(settings.getFloat("tessellationTolerance"), 0.06);
    settings.setFromAssignment("tessellationTolerance=0.3");
    EXPECT_DOUBLE_EQ(settings.getFloat("tessellationTolerance"), 0.3);
    settings.setFromAssignment("maxSegmentsPerSpan=5");
    EXPECT_EQ(settings.getInt("maxSegmentsPerSpan"), 5);
}

TEST(RenderSettings, FromAssignmentsAppliesThemInOrderOverTheComplexity) {
    RenderSettings settings = RenderSettings::fromAssignments(
        Complexity::Medium, {"pixelsPerSegment=3", "transparency=exact", "transparency=opaque"});
    EXPECT_EQ(settings.complexity(), Complexity::Medium);
    EXPECT_EQ(settings.getFloat("pixelsPerSegment"), 3.0);
    EXPECT_EQ(settings.getInt("maxSegmentsPerSpan"), 16);  // medium's
    EXPECT_EQ(settings.getToken("transparency"), "opaque");
    EXPECT_THROW(RenderSettings::fromAssignments(Complexity::Low, {"bogus=1"}), std::invalid_argument);
}

TEST(RenderSettings, BadAssignmentsGiveOneLineReasons) {
    RenderSettings settings;
    EXPECT_EQ(errorOf(settings, "maxSegmentsPerSpan=100"), "setting 'maxSegmentsPerSpan' must be in [1, 64], got 100");
    EXPECT_EQ(errorOf(settings, "maxSegmentsPerSpan=2.5"), "setting 'maxSegmentsPerSpan' expects an integer, got '2.5'");
    EXPECT_EQ(errorOf(settings, "kajiyaKay:specular=shiny"), "setting 'kajiyaKay:specular' expects a number, got 'shiny'");
    EXPECT_EQ(errorOf(settings, "cameraLight=maybe"), "setting 'cameraLight' expects one of auto, on, off, got 'maybe'");
    EXPECT_EQ(errorOf(settings, "noEquals"), "setting 'noEquals' is not of the form NAME=VALUE");
    EXPECT_EQ(errorOf(settings, "bogus=1").rfind("unknown setting 'bogus' (known settings: tessellation,", 0), 0u)
        << errorOf(settings, "bogus=1");
    EXPECT_EQ(errorOf(settings, "pixelsPerSegment=nan"), "setting 'pixelsPerSegment' expects a number, got 'nan'");
    EXPECT_EQ(errorOf(settings, "msaaSamples=3"), "setting 'msaaSamples' expects one of 0, 2, 4, 8, got '3'");
    EXPECT_EQ(errorOf(settings, "msaaSamples=4"), "");
    EXPECT_EQ(errorOf(settings, "transparency=sorted"),
              "setting 'transparency' expects one of binSorted, exact, unsorted, opaque, got 'sorted'");
}
