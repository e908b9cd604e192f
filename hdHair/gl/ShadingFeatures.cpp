#include "hdHair/gl/ShadingFeatures.h"

#include <algorithm>

namespace hdhair::gl {

const std::vector<ShadingFeatureSwitch>& shadingFeatureSwitches() {
    static const std::vector<ShadingFeatureSwitch> switches{
        {ShadingFeature::Shade, "HDHAIR_FEATURE_SHADE", "shade"},
        {ShadingFeature::KajiyaKay, "HDHAIR_FEATURE_KAJIYA_KAY", "kajiyaKay"},
        {ShadingFeature::MarschnerTabled, "HDHAIR_FEATURE_MARSCHNER_TABLED", "marschnerTabled"},
        {ShadingFeature::MarschnerAnalytic, "HDHAIR_FEATURE_MARSCHNER_ANALYTIC", "marschnerAnalytic"},
        {ShadingFeature::PerPointParameters, "HDHAIR_FEATURE_PER_POINT_PARAMETERS", "perPointParameters"},
        {ShadingFeature::SrbfAbsorption, "HDHAIR_FEATURE_SRBF_ABSORPTION", "srbfAbsorption"},
        {ShadingFeature::DualScattering, "HDHAIR_FEATURE_DUAL_SCATTERING", "dualScattering"},
        {ShadingFeature::LocalLights, "HDHAIR_FEATURE_LOCAL_LIGHTS", "localLights"},
        {ShadingFeature::SrbfLights, "HDHAIR_FEATURE_SRBF_LIGHTS", "srbfLights"},
        {ShadingFeature::UniformDome, "HDHAIR_FEATURE_UNIFORM_DOME", "uniformDome"},
        {ShadingFeature::DeepOpacity, "HDHAIR_FEATURE_DEEP_OPACITY", "deepOpacity"},
        {ShadingFeature::ShadowReference, "HDHAIR_FEATURE_SHADOW_REFERENCE", "shadowReference"},
        {ShadingFeature::BilinearShadows, "HDHAIR_FEATURE_BILINEAR_SHADOWS", "bilinearShadows"},
        {ShadingFeature::MeshOccluders, "HDHAIR_FEATURE_MESH_OCCLUDERS", "meshOccluders"},
        {ShadingFeature::SrbfShadowTaps, "HDHAIR_FEATURE_SRBF_SHADOW_TAPS", "srbfShadowTaps"},
        {ShadingFeature::SrbfShadowMipmap, "HDHAIR_FEATURE_SRBF_SHADOW_MIPMAP", "srbfShadowMipmap"},
        {ShadingFeature::DensityVolume, "HDHAIR_FEATURE_DENSITY_VOLUME", "densityVolume"},
        {ShadingFeature::VolumeBackScattering, "HDHAIR_FEATURE_VOLUME_BACK_SCATTERING", "volumeBackScattering"},
    };
    return switches;
}

ShadingFeatures ShadingFeatures::all() {
    ShadingFeatures features;
    for (const ShadingFeatureSwitch& entry : shadingFeatureSwitches()) features.add(entry.feature);
    return features;
}

std::string ShadingFeatures::glsl() const {
    // The guard the file has, so that a program including it twice is fine.
    std::string text = "#ifndef HDHAIR_SHADING_FEATURES\n#define HDHAIR_SHADING_FEATURES 1\n";
    for (const ShadingFeatureSwitch& entry : shadingFeatureSwitches())
        text += std::string("#define ") + entry.macro + (has(entry.feature) ? " 1\n" : " 0\n");
    if (shadowLayers_ > 0) text += "#define HDHAIR_SHADOW_LAYERS " + std::to_string(shadowLayers_) + "\n";
    if (vertexShadowLights_ > 0) {
        text += "#define HDHAIR_VERTEX_SHADOWS " + std::to_string(vertexShadowLights_) + "\n";
        text += "#define HDHAIR_VERTEX_SHADOW_VECTORS " + std::to_string((vertexShadowLights_ + 3) / 4) + "\n";
    }
    if (strandLines_) text += "#define HDHAIR_STRAND_LINES 1\n";
    return text + "#endif\n";
}

std::string ShadingFeatures::describe() const {
    std::string text;
    for (const ShadingFeatureSwitch& entry : shadingFeatureSwitches())
        if (has(entry.feature)) text += (text.empty() ? "" : " ") + std::string(entry.name);
    if (text.empty()) text = "none";
    if (shadowLayers_ > 0) text += " shadowLayers=" + std::to_string(shadowLayers_);
    if (vertexShadowLights_ > 0) text += " vertexShadows=" + std::to_string(vertexShadowLights_);
    if (strandLines_) text += " strandLines";
    return text;
}

}  // namespace hdhair::gl
