#include "hdHair/render/StrandShadingFeatures.h"

#include <algorithm>

#include <glm/geometric.hpp>

#include "hdHair/gl/UniformBlocks.h"
#include "hdHair/render/SrbfMaterialTables.h"

namespace hdhair {

namespace {

// The lights a batch's draw reads: its range, at most a pass's worth.
std::pair<size_t, size_t> batchLights(const FrameRecipe& recipe, size_t batch) {
    const auto [begin, end] = recipe.lighting.batches[batch];
    return {begin, std::min(end, begin + size_t(gl::kMaxLightsPerPass))};
}

}  // namespace

gl::ShadingFeatures materialShadingFeatures(const std::vector<HairMaterial>& materials, bool domeTables) {
    using gl::ShadingFeature;
    gl::ShadingFeatures features;
    for (const HairMaterial& material : materials) {
        if (material.model == ShadingModel::Marschner) {
            features.add(material.analyticAzimuthal ? ShadingFeature::MarschnerAnalytic
                                                    : ShadingFeature::MarschnerTabled);
            if (domeTables && srbfAbsorbsPerFragment(material)) features.add(ShadingFeature::SrbfAbsorption);
            if (material.dualScattering) features.add(ShadingFeature::DualScattering);
        } else if (material.model == ShadingModel::KajiyaKay) {
            features.add(ShadingFeature::KajiyaKay);
        }
        if (material.perPoint()) features.add(ShadingFeature::PerPointParameters);
    }
    return features;
}

gl::ShadingFeatures batchShadingFeatures(const FrameRecipe& recipe, size_t batch,
                                         const gl::ShadingFeatures& materials) {
    using gl::ShadingFeature;
    gl::ShadingFeatures features;
    features.add(ShadingFeature::Shade).add(materials);
    if (batch == 0 && glm::length(recipe.lighting.lights.uniformDome) > 0.0f) features.add(ShadingFeature::UniformDome);
    const ShadowPlan& shadows = recipe.shadows;
    if (materials.has(ShadingFeature::DualScattering) && shadows.volumeBackScattering && shadows.usesVolume())
        features.add(ShadingFeature::VolumeBackScattering);
    if (features.has(ShadingFeature::UniformDome) && shadows.volumeDomeOcclusion && shadows.usesVolume())
        features.add(ShadingFeature::DensityVolume);
    const auto [begin, end] = batchLights(recipe, batch);
    for (size_t light = begin; light < end; ++light) {
        const bool srbf = recipe.lighting.lights.lights[light].isSrbf();
        if (srbf) features.add(ShadingFeature::SrbfLights);
        else if (recipe.lighting.lights.lights[light].isLocal)
            features.add(ShadingFeature::LocalLights);
        const int shadow = shadows.shadowOf(light);
        if (shadow < 0) continue;
        const PlannedShadow& planned = shadows.lights[size_t(shadow)];
        if (shadows.isMeshMapped(planned)) features.add(ShadingFeature::MeshOccluders);
        if (planned.byVolume && shadows.usesVolume()) features.add(ShadingFeature::DensityVolume);
        if (!shadows.isMapped(planned)) continue;
        if (shadows.mode == ShadowMode::Reference) {
            features.add(ShadingFeature::ShadowReference);
        } else {
            features.add(ShadingFeature::DeepOpacity);
            features.setShadowLayers(shadows.layers);
        }
        if (shadows.bilinear) features.add(ShadingFeature::BilinearShadows);
        if (srbf)
            features.add(shadows.convolvedOpacity ? ShadingFeature::SrbfShadowMipmap : ShadingFeature::SrbfShadowTaps);
    }
    return features;
}

int batchVertexShadowLights(const FrameRecipe& recipe, size_t batch) {
    const ShadowPlan& shadows = recipe.shadows;
    if (shadows.mode != ShadowMode::DeepOpacity) return 0;
    const auto [begin, end] = batchLights(recipe, batch);
    int looked = 0;
    for (size_t light = begin; light < end; ++light) {
        const int shadow = shadows.shadowOf(light);
        if (shadow >= 0 && shadows.isMapped(shadows.lights[size_t(shadow)])) looked = int(light - begin) + 1;
    }
    return looked;
}

}  // namespace hdhair
