#include <algorithm>
#include <set>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <variant>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hdHair/plan/RenderSettings.h"
#include "hdHair/plan/SettingOrigins.h"

using namespace hdhair;

namespace {

// Where a descriptor's field lies in `values`.
const void* fieldAddress(const SettingDescriptor& descriptor, const SettingValues& values) {
    return std::visit(
        [&](auto field) -> const void* {
            if constexpr (std::is_same_v<decltype(field), TokenField>) return field.address(values);
            else return &(values.*field);
        },
        descriptor.field);
}

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

// Each descriptor fills its own field of SettingValues, of its own type.
TEST(RenderSettings, EveryDescriptorFillsOneTypedFieldOfItsType) {
    std::set<size_t> fields;
    for (const SettingDescriptor& descriptor : RenderSettings::descriptors()) {
        EXPECT_EQ(descriptor.field.index(), size_t(descriptor.type)) << descriptor.name;
        // Distinct fields have distinct offsets in one SettingValues.
        SettingValues values;
        const size_t offset = size_t(static_cast<const char*>(fieldAddress(descriptor, values)) -
                                     reinterpret_cast<const char*>(&values));
        EXPECT_TRUE(fields.insert(offset).second) << descriptor.name << " shares a field";
    }
}

// The typed values are the effective values, through whatever chose them.
TEST(RenderSettings, TypedValuesFollowAssignmentsComplexityAndPresets) {
    RenderSettings settings;
    EXPECT_EQ(settings.values().shadowLayers, 3);
    EXPECT_EQ(settings.values().cameraLight, CameraLightSetting::Auto);
    EXPECT_TRUE(settings.values().specializeShaders);
    settings.set("quality", "high");
    EXPECT_EQ(settings.values().shadowLayers, settings.getInt("shadowLayers"));
    EXPECT_NE(settings.values().shadowLayers, 3);
    settings.setComplexity(Complexity::High);
    EXPECT_EQ(settings.values().maxSegmentsPerSpan, 32);
    settings.setFromAssignment("kajiyaKay:shininess=12.5");
    EXPECT_DOUBLE_EQ(settings.values().kajiyaKayShininess, 12.5);
    settings.setFromAssignment("passTimings=on");
    EXPECT_TRUE(settings.values().passTimings);
    const nlohmann::json json = settings.toJson();
    for (const SettingDescriptor& descriptor : RenderSettings::descriptors())
        std::visit(
            [&](auto field) {
                if constexpr (std::is_same_v<decltype(field), TokenField>)
                    EXPECT_EQ(json[descriptor.name], field.read(settings.values())) << descriptor.name;
                else
                    EXPECT_EQ(json[descriptor.name], settings.values().*field) << descriptor.name;
            },
            descriptor.field);
}

// Every token setting is an enum whose table is the descriptor's list: each
// listed value parses, reads back as itself, and the default is one of them.
TEST(RenderSettings, TokenSettingsAreEnumsListedFromTheirTables) {
    size_t tokenSettings = 0;
    for (const SettingDescriptor& descriptor : RenderSettings::descriptors()) {
        const TokenField* field = std::get_if<TokenField>(&descriptor.field);
        ASSERT_EQ(field != nullptr, descriptor.type == SettingType::Token) << descriptor.name;
        if (!field) continue;
        ++tokenSettings;
        EXPECT_EQ(descriptor.tokens, field->names()) << descriptor.name;
        EXPECT_NE(std::find(descriptor.tokens.begin(), descriptor.tokens.end(), descriptor.defaultValue),
                  descriptor.tokens.end())
            << descriptor.name;
        for (const std::string& token : descriptor.tokens) {
            RenderSettings settings;
            settings.set(descriptor.name, token);
            EXPECT_STREQ(field->read(settings.values()), token.c_str()) << descriptor.name;
            EXPECT_EQ(settings.getToken(descriptor.name), token);
        }
    }
    EXPECT_EQ(tokenSettings, 21u);
    // A misspelt value is refused by the table, whatever its case.
    Quality quality = Quality::Default;
    EXPECT_FALSE(parseToken("High", &quality));
    EXPECT_EQ(quality, Quality::Default);
    EXPECT_STREQ(toString(ShadowMode::DeepOpacity), "deepOpacity");
    EXPECT_EQ(tokenChoices<ShadingModel>(), "kajiyaKay, marschner or flat");
}

// setValue sets a setting by its field, as if set explicitly, with the
// value exactly (no text in between loses digits).
TEST(RenderSettings, SetValueSetsTheFieldsSettingExplicitly) {
    RenderSettings settings;
    settings.setValue(&SettingValues::shadowMode, ShadowMode::Off);
    settings.setValue(&SettingValues::pixelsPerSegment, 16.333333333333332);
    settings.setValue(&SettingValues::lightsPerPass, 16);
    settings.setValue(&SettingValues::passTimings, true);
    EXPECT_EQ(settings.values().shadowMode, ShadowMode::Off);
    EXPECT_EQ(settings.getToken("shadowMode"), "off");
    EXPECT_TRUE(settings.isExplicitlySet("shadowMode"));
    EXPECT_EQ(settings.values().pixelsPerSegment, 16.333333333333332);
    EXPECT_EQ(settings.values().lightsPerPass, 16);
    EXPECT_TRUE(settings.values().passTimings);
    EXPECT_EQ(RenderSettings::descriptorOf(&SettingValues::marschnerAzimuthal).name, "marschner:azimuthal");
    EXPECT_EQ(RenderSettings::descriptorOf(&SettingValues::kajiyaKayShininess).name, "kajiyaKay:shininess");
    // Out of range is refused as from text.
    EXPECT_THROW(settings.setValue(&SettingValues::lightsPerPass, 17), std::invalid_argument);
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
    EXPECT_EQ(errorOf(settings, "bogus=1").rfind("unknown setting 'bogus' (known settings: quality, tessellation,", 0), 0u)
        << errorOf(settings, "bogus=1");
    EXPECT_EQ(errorOf(settings, "pixelsPerSegment=nan"), "setting 'pixelsPerSegment' expects a number, got 'nan'");
    EXPECT_EQ(errorOf(settings, "msaaSamples=3"), "setting 'msaaSamples' expects one of 0, 2, 4, 8, got '3'");
    EXPECT_EQ(errorOf(settings, "msaaSamples=4"), "");
    EXPECT_EQ(errorOf(settings, "transparency=sorted"),
              "setting 'transparency' expects one of binSorted, exact, unsorted, opaque, got 'sorted'");
}

// quality=default must be today's defaults exactly, at every complexity: the
// baselines and every user who never names a preset depend on it.
TEST(QualityPresets, DefaultIsTheDefaultsExactly) {
    EXPECT_TRUE(presetSettings(Quality::Default).empty());
    for (Complexity complexity : {Complexity::Low, Complexity::Medium, Complexity::High, Complexity::VeryHigh}) {
        const RenderSettings none = RenderSettings::fromAssignments(complexity, {});
        const RenderSettings named = RenderSettings::fromAssignments(complexity, {"quality=default"});
        nlohmann::json a = none.toJson(), b = named.toJson();
        a.erase("quality");
        b.erase("quality");
        EXPECT_EQ(a, b) << toString(complexity);
    }
    EXPECT_EQ(RenderSettings().getToken("quality"), "default");
    EXPECT_EQ(RenderSettings().getInt("supersampling"), 1);
    EXPECT_EQ(RenderSettings().getToken("exactOverflow"), "fallBack");
}

// Every preset names real settings with valid values, and each one other
// than default changes something.
TEST(QualityPresets, EveryPresetIsValidSettings) {
    for (Quality quality : {Quality::Preview, Quality::High, Quality::Reference}) {
        RenderSettings settings;
        for (const auto& [name, value] : presetSettings(quality)) {
            EXPECT_NO_THROW(settings.set(name, value)) << toString(quality) << " " << name << "=" << value;
            EXPECT_NE(name, "quality");
        }
        const RenderSettings preset = RenderSettings::fromAssignments(Complexity::Low, {std::string("quality=") + toString(quality)});
        for (const auto& [name, value] : presetSettings(quality)) {
            EXPECT_EQ(preset.getToken(name), value) << toString(quality) << " " << name;
            EXPECT_EQ(preset.origin(name).source, SettingSource::Preset) << name;
        }
        EXPECT_NE(preset.toJson(), RenderSettings().toJson()) << toString(quality);
    }
}

// reference is the most exact hdHair can be: exact transparency that fails
// instead of falling back, reference shadows, analytic Marschner, the
// tightest tolerance the setting allows, the most segments a span may get,
// and supersampling.
TEST(QualityPresets, ReferenceIsTheMostExactSettings) {
    const RenderSettings reference = RenderSettings::fromAssignments(Complexity::Low, {"quality=reference"});
    EXPECT_EQ(reference.getToken("transparency"), "exact");
    EXPECT_EQ(reference.getToken("exactOverflow"), "fail");
    EXPECT_EQ(reference.getToken("shadowMode"), "reference");
    EXPECT_EQ(reference.getToken("marschner:azimuthal"), "analytic");
    EXPECT_EQ(reference.getToken("tessellation"), "screenError");
    EXPECT_DOUBLE_EQ(reference.getFloat("tessellationTolerance"), RenderSettings::find("tessellationTolerance")->minimum);
    EXPECT_DOUBLE_EQ(reference.getFloat("shadowTessellationTolerance"),
                     RenderSettings::find("shadowTessellationTolerance")->minimum);
    EXPECT_EQ(reference.getInt("maxSegmentsPerSpan"), int(RenderSettings::find("maxSegmentsPerSpan")->maximum));
    EXPECT_GT(reference.getInt("supersampling"), 1);
    // Each preset is at least as exact as the one below it where they share a setting.
    const RenderSettings preview = RenderSettings::fromAssignments(Complexity::Low, {"quality=preview"});
    const RenderSettings high = RenderSettings::fromAssignments(Complexity::Low, {"quality=high"});
    const RenderSettings defaults;
    for (const char* name : {"tessellationTolerance"}) {
        EXPECT_GT(preview.getFloat(name), defaults.getFloat(name));
        EXPECT_LT(high.getFloat(name), defaults.getFloat(name));
        EXPECT_LT(reference.getFloat(name), high.getFloat(name));
    }
    for (const char* name : {"maxSegmentsPerSpan", "supersampling"}) {
        EXPECT_LE(preview.getInt(name), defaults.getInt(name)) << name;
        EXPECT_GE(high.getInt(name), defaults.getInt(name)) << name;
        EXPECT_GE(reference.getInt(name), high.getInt(name)) << name;
    }
    EXPECT_LT(preview.getInt("sortBins"), defaults.getInt("sortBins"));
    EXPECT_EQ(preview.getToken("shadowMode"), "off");  // as the interactive previews draw
    EXPECT_GT(high.getInt("shadowLayers"), defaults.getInt("shadowLayers"));
}

// An explicit setting wins over the preset wherever it comes from, and a
// complexity above low wins over it for the settings complexity scales;
// low, every host's default, does not.
TEST(QualityPresets, ExplicitSettingsAndAComplexityAboveLowWin) {
    RenderSettings settings = RenderSettings::fromAssignments(Complexity::Low, {"shadowLayers=3", "quality=high"});
    EXPECT_EQ(settings.getInt("shadowLayers"), 3);
    EXPECT_EQ(settings.origin("shadowLayers").source, SettingSource::Explicit);
    EXPECT_EQ(settings.origin("shadowLayers").overriddenPreset, "15");
    EXPECT_EQ(settings.getInt("supersampling"), 2);
    EXPECT_DOUBLE_EQ(settings.getFloat("tessellationTolerance"), 0.06);
    EXPECT_EQ(settings.origin("tessellationTolerance").source, SettingSource::Preset);

    settings.setComplexity(Complexity::VeryHigh);
    EXPECT_DOUBLE_EQ(settings.getFloat("tessellationTolerance"), 0.015);
    EXPECT_EQ(settings.getInt("maxSegmentsPerSpan"), 64);
    EXPECT_EQ(settings.origin("tessellationTolerance").source, SettingSource::Complexity);
    EXPECT_EQ(settings.origin("tessellationTolerance").overriddenPreset, "0.06");
    EXPECT_EQ(settings.getInt("supersampling"), 2);  // complexity does not scale it: the preset's

    settings.setComplexity(Complexity::Medium);
    EXPECT_DOUBLE_EQ(settings.getFloat("tessellationTolerance"), 0.06);  // the preset's value, but chosen
    EXPECT_EQ(settings.origin("tessellationTolerance").source, SettingSource::Complexity);

    // Settings no preset touches keep their complexity values at low.
    const RenderSettings low = RenderSettings::fromAssignments(Complexity::Low, {"quality=reference"});
    EXPECT_EQ(low.getInt("meshRefineLevel"), 0);
    EXPECT_EQ(low.origin("meshRefineLevel").source, SettingSource::Complexity);
    EXPECT_EQ(low.origin("kajiyaKay:specular").source, SettingSource::Default);
    EXPECT_EQ(low.origin("quality").source, SettingSource::Explicit);
}

TEST(QualityPresets, UnknownPresetsGiveOneLineReasons) {
    RenderSettings settings;
    EXPECT_EQ(errorOf(settings, "quality=ultra"),
              "setting 'quality' expects one of preview, default, high, reference, got 'ultra'");
    EXPECT_EQ(errorOf(settings, "supersampling=9"), "setting 'supersampling' must be in [1, 8], got 9");
    EXPECT_EQ(errorOf(settings, "exactOverflow=ignore"),
              "setting 'exactOverflow' expects one of fallBack, fail, got 'ignore'");
    Quality quality;
    EXPECT_FALSE(parseToken("Reference", &quality));
    EXPECT_TRUE(parseToken("reference", &quality));
    EXPECT_EQ(quality, Quality::Reference);
}

// --explain's lines: every setting a preset, an explicit value or a complexity
// above low chose, with what chose it and the preset value that lost.
TEST(SettingOrigins, ExplainNamesWhatChoseEachSetting) {
    RenderSettings settings = RenderSettings::fromAssignments(Complexity::High, {"quality=reference", "sortBins=64"});
    const std::string text = describeSettingOrigins(settings);
    EXPECT_NE(text.find("quality=reference, complexity high"), std::string::npos) << text;
    EXPECT_NE(text.find("transparency           exact        quality=reference"), std::string::npos) << text;
    EXPECT_NE(text.find("sortBins               64           explicit\n"), std::string::npos) << text;
    EXPECT_NE(text.find("tessellationTolerance  0.03         complexity high (wins over quality=reference's 0.001)"),
              std::string::npos)
        << text;
    EXPECT_EQ(text.find("kajiyaKay:specular"), std::string::npos) << text;  // a default
    const nlohmann::json json = settingOriginsJson(settings);
    EXPECT_EQ(json["supersampling"]["source"], "quality=reference");
    EXPECT_EQ(json["kajiyaKay:specular"]["source"], "default");
    EXPECT_EQ(json["tessellationTolerance"]["overriddenPreset"], "0.001");
    EXPECT_EQ(json.size(), RenderSettings::descriptors().size());
    // With no preset and complexity low, nothing but the header is printed.
    const std::string plain = describeSettingOrigins(RenderSettings());
    EXPECT_EQ(plain, "  quality=default, complexity low\n");
}
