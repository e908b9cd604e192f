#pragma once
// Every render setting's effective value, typed: what the planners, the
// passes' inputs and the tools read. RenderSettings fills it once from the
// descriptors (each descriptor names the field it fills, RenderSettings.cpp),
// so a misspelt setting is a compile error and a setting's name exists once,
// in its descriptor. Reading by name (RenderSettings::getToken and friends)
// is for what is generic over the table: --stats, --explain, Hydra's
// render-setting map, the quality presets.

#include <string>
#include <variant>

namespace hdhair {

struct SettingValues {
    std::string quality;
    std::string tessellation;
    double tessellationTolerance = 0.0;
    double pixelsPerSegment = 0.0;
    int maxSegmentsPerSpan = 0;
    int meshRefineLevel = 0;
    std::string transparency;
    int sortBins = 0;
    double minPixelWidth = 0.0;
    int msaaSamples = 0;
    int exactMemoryMB = 0;
    std::string exactOverflow;
    std::string strandRaster;
    double strandRasterMaxPixelWidth = 0.0;
    double strandRasterMaxFragmentsPerSpan = 0.0;
    int strandRasterMemoryMB = 0;
    int supersampling = 1;
    int lightsPerPass = 0;
    std::string shadingModel;
    double kajiyaKayDiffuse = 0.0;    // kajiyaKay:diffuse
    double kajiyaKaySpecular = 0.0;   // kajiyaKay:specular
    double kajiyaKayShininess = 0.0;  // kajiyaKay:shininess
    std::string marschnerAzimuthal;   // marschner:azimuthal
    std::string multipleScattering;
    double multipleScatteringForwardDensity = 0.0;  // multipleScattering:forwardDensity
    double multipleScatteringBackDensity = 0.0;     // multipleScattering:backDensity
    std::string shadowMode;
    int shadowLayers = 0;
    int shadowMapResolution = 0;
    double shadowTessellationTolerance = 0.0;
    std::string shadowStrandLines;
    int shadowMemoryMB = 0;
    std::string shadowLayerSpacing;
    double shadowLayerDepth = 0.0;
    std::string shadowFilter;
    std::string shadowSampling;
    std::string domeLighting;
    int domeLights = 0;
    std::string domeShadowFilter;
    int domeSampledLights = 0;
    int domeShadowLights = 0;
    std::string cameraLight;
    std::string cameraLightShadows;
    std::string drawBatching;
    bool specializeShaders = true;
    bool passTimings = false;
    std::string framing;
    int interactiveBudgetMs = 0;
    std::string renderingSpace;
};

// The field a descriptor fills; its alternative matches the descriptor's
// SettingType (Float, Int, Bool, Token in that order).
using SettingField = std::variant<double SettingValues::*, int SettingValues::*, bool SettingValues::*,
                                  std::string SettingValues::*>;

}  // namespace hdhair
