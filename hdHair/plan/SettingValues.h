#pragma once
// Every render setting's effective value, typed: what the planners, the
// passes' inputs and the tools read. RenderSettings fills it once from the
// descriptors (each descriptor names the field it fills, RenderSettings.cpp),
// so a misspelt setting is a compile error and a setting's name exists once,
// in its descriptor. Token settings are enums (SettingTokens.h): no code
// compares a setting with text. Reading by name (RenderSettings::getToken and friends)
// is for what is generic over the table: --stats, --explain, Hydra's
// render-setting map, the quality presets.

#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "hdHair/base/TokenTable.h"
#include "hdHair/image/ColorSpaces.h"
#include "hdHair/plan/SettingTokens.h"

namespace hdhair {

struct SettingValues {
    Quality quality = Quality::Default;
    Tessellation tessellation = Tessellation::ScreenError;
    double tessellationTolerance = 0.0;
    double pixelsPerSegment = 0.0;
    int maxSegmentsPerSpan = 0;
    int meshRefineLevel = 0;
    TransparencyPath transparency = TransparencyPath::BinSorted;
    int sortBins = 0;
    double minPixelWidth = 0.0;
    int msaaSamples = 0;
    int exactMemoryMB = 0;
    ExactOverflow exactOverflow = ExactOverflow::FallBack;
    StrandRasterSetting strandRaster = StrandRasterSetting::Auto;
    double strandRasterMaxPixelWidth = 0.0;
    double strandRasterMaxFragmentsPerSpan = 0.0;
    int strandRasterMemoryMB = 0;
    int supersampling = 1;
    int lightsPerPass = 0;
    ShadingModel shadingModel = ShadingModel::KajiyaKay;
    double kajiyaKayDiffuse = 0.0;    // kajiyaKay:diffuse
    double kajiyaKaySpecular = 0.0;   // kajiyaKay:specular
    double kajiyaKayShininess = 0.0;  // kajiyaKay:shininess
    MarschnerAzimuthal marschnerAzimuthal = MarschnerAzimuthal::Auto;  // marschner:azimuthal
    MultipleScattering multipleScattering = MultipleScattering::Auto;
    double multipleScatteringForwardDensity = 0.0;  // multipleScattering:forwardDensity
    double multipleScatteringBackDensity = 0.0;     // multipleScattering:backDensity
    DualScatteringLocalTerm multipleScatteringLocalTerm = DualScatteringLocalTerm::DensityVolume;
    ShadowMode shadowMode = ShadowMode::Auto;
    int densityVolumeMemoryMB = 16;
    int shadowLayers = 0;
    int shadowMapResolution = 0;
    double shadowTessellationTolerance = 0.0;
    ShadowStrandLines shadowStrandLines = ShadowStrandLines::Auto;
    int shadowMemoryMB = 0;
    ShadowLayerSpacing shadowLayerSpacing = ShadowLayerSpacing::Linear;
    double shadowLayerDepth = 0.0;
    ShadowFilter shadowFilter = ShadowFilter::Bilinear;
    ShadowSampling shadowSampling = ShadowSampling::Auto;
    DomeLightingMode domeLighting = DomeLightingMode::Srbf;
    int domeLights = 0;
    DomeShadowFilter domeShadowFilter = DomeShadowFilter::Mipmap;
    int domeSampledLights = 0;
    int domeShadowLights = 0;
    CameraLightSetting cameraLight = CameraLightSetting::Auto;
    CameraLightShadows cameraLightShadows = CameraLightShadows::Off;
    DrawBatching drawBatching = DrawBatching::Auto;
    bool specializeShaders = true;
    bool passTimings = false;
    FramingStyle framing = FramingStyle::FitAll;
    int interactiveBudgetMs = 0;
    RenderingSpace renderingSpace = RenderingSpace::LinearRec709;
};

// A token setting's field, through its enum's table: how validated text is
// stored in it, how it reads back, and every value it takes.
struct TokenField {
    void (*assign)(SettingValues& values, const std::string& text) = nullptr;
    const char* (*read)(const SettingValues& values) = nullptr;
    std::vector<std::string> (*names)() = nullptr;
    // Whether this is the field `member` (RenderSettings::setValue finds its descriptor so).
    const void* (*address)(const SettingValues& values) = nullptr;
};

// The TokenField of an enum member of SettingValues: tokenField<&SettingValues::shadowMode>().
template <auto Member>
TokenField tokenField() {
    using Enum = std::remove_cv_t<std::remove_reference_t<decltype(std::declval<SettingValues&>().*Member)>>;
    static_assert(HasTokenTable<Enum>::value, "a token setting's enum needs a TokenTable");
    TokenField field;
    field.assign = [](SettingValues& values, const std::string& text) { parseToken(text, &(values.*Member)); };
    field.read = [](const SettingValues& values) { return tokenName(values.*Member); };
    field.names = [] { return tokenNames<Enum>(); };
    field.address = [](const SettingValues& values) -> const void* { return &(values.*Member); };
    return field;
}

// The field a descriptor fills; its alternative matches the descriptor's
// SettingType (Float, Int, Bool, Token in that order).
using SettingField = std::variant<double SettingValues::*, int SettingValues::*, bool SettingValues::*, TokenField>;

}  // namespace hdhair
