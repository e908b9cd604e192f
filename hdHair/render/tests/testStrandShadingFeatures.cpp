// Which parts of the strand shading a frame's draws reach, read from its
// plan (StrandShadingFeatures.h): each planned condition turns on its
// feature and nothing else. That the specialised programs draw what the
// complete one draws is testenv's testShaderSpecialization.

#include <gtest/gtest.h>

#include "hdHair/gl/tests/ShadingFeatureSets.h"
#include "hdHair/render/StrandShadingFeatures.h"

using namespace hdhair;
using gl::ShadingFeature;
using gl::ShadingFeatures;

using gl::only;

namespace {

// A plan of `count` distant lights in one batch, without shadows.
FrameRecipe litPlan(size_t count = 1) {
    FrameRecipe plan;
    plan.lighting.lights.lights.resize(count);
    plan.lighting.batches = {{0, count}};
    plan.shadows.mode = ShadowMode::Off;
    return plan;
}

// Gives light `light` a planned shadow with a map in `slot` (-1: none).
void castFrom(FrameRecipe& plan, size_t light, int slot = 0) {
    PlannedShadow shadow;
    shadow.light = light;
    shadow.view.valid = true;
    shadow.slot = slot;
    plan.shadows.lights.push_back(shadow);
}

ShadingFeatures featuresOf(const FrameRecipe& plan, ShadingFeatures materials = {}) {
    return batchShadingFeatures(plan, 0, materials);
}

HairMaterial material(ShadingModel model, uint32_t varies = kNothingVaries, bool analytic = false) {
    HairMaterial entry;
    entry.model = model;
    entry.varies = varies;
    entry.analyticAzimuthal = analytic;
    return entry;
}

}  // namespace

TEST(StrandShadingFeatures, MaterialsCallForTheirModelsAndParameters) {
    using Model = ShadingModel;
    EXPECT_EQ(materialShadingFeatures({}, false), ShadingFeatures());
    EXPECT_EQ(materialShadingFeatures({material(Model::Flat)}, false), ShadingFeatures());  // nothing to compile
    EXPECT_EQ(materialShadingFeatures({material(Model::KajiyaKay)}, false), only({ShadingFeature::KajiyaKay}));
    EXPECT_EQ(materialShadingFeatures({material(Model::Marschner)}, false), only({ShadingFeature::MarschnerTabled}));
    EXPECT_EQ(materialShadingFeatures({material(Model::Marschner, kNothingVaries, true)}, false),
              only({ShadingFeature::MarschnerAnalytic}));
    EXPECT_EQ(materialShadingFeatures({material(Model::KajiyaKay, kAbsorptionVaries)}, false),
              only({ShadingFeature::KajiyaKay, ShadingFeature::PerPointParameters}));
    // Absorption per fragment under a dome: Marschner's, and only with the dome's tables.
    const HairMaterial varying = material(Model::Marschner, kAbsorptionVaries);
    EXPECT_EQ(materialShadingFeatures({varying}, true),
              only({ShadingFeature::MarschnerTabled, ShadingFeature::PerPointParameters, ShadingFeature::SrbfAbsorption}));
    EXPECT_EQ(materialShadingFeatures({varying}, false),
              only({ShadingFeature::MarschnerTabled, ShadingFeature::PerPointParameters}));
    EXPECT_EQ(materialShadingFeatures({material(Model::KajiyaKay, kAbsorptionVaries)}, true),
              only({ShadingFeature::KajiyaKay, ShadingFeature::PerPointParameters}));
    EXPECT_EQ(materialShadingFeatures({material(Model::Flat), material(Model::KajiyaKay), material(Model::Marschner)},
                                      false),
              only({ShadingFeature::KajiyaKay, ShadingFeature::MarschnerTabled}));
}

TEST(StrandShadingFeatures, EachPlannedConditionTurnsOnItsFeature) {
    const ShadingFeatures shade = only({ShadingFeature::Shade});
    EXPECT_EQ(featuresOf(litPlan()), shade);
    EXPECT_EQ(featuresOf(litPlan(), only({ShadingFeature::KajiyaKay})),
              only({ShadingFeature::Shade, ShadingFeature::KajiyaKay}));

    FrameRecipe dome = litPlan();
    dome.lighting.lights.uniformDome = glm::vec3(0.5f);
    EXPECT_EQ(featuresOf(dome), only({ShadingFeature::Shade, ShadingFeature::UniformDome}));
    dome.lighting.batches = {{0, 1}, {1, 1}};  // the uniform term belongs to the first batch only
    EXPECT_EQ(batchShadingFeatures(dome, 1, {}), shade);

    FrameRecipe local = litPlan();
    local.lighting.lights.lights[0].isLocal = true;
    EXPECT_EQ(featuresOf(local), only({ShadingFeature::Shade, ShadingFeature::LocalLights}));
    FrameRecipe lobe = litPlan();
    lobe.lighting.lights.lights[0].srbfBandwidth = 8.0f;
    EXPECT_EQ(featuresOf(lobe), only({ShadingFeature::Shade, ShadingFeature::SrbfLights}));
    // Lights of another batch are not read.
    FrameRecipe later = litPlan(2);
    later.lighting.lights.lights[1].srbfBandwidth = 8.0f;
    later.lighting.batches = {{0, 1}, {1, 2}};
    EXPECT_EQ(featuresOf(later), shade);

    FrameRecipe deep = litPlan();
    deep.shadows.mode = ShadowMode::DeepOpacity;
    deep.shadows.bilinear = false;
    EXPECT_EQ(featuresOf(deep), shade) << "a mode with no light that has a map looks nothing up";
    castFrom(deep, 0, -1);
    EXPECT_EQ(featuresOf(deep), shade) << "a planned shadow the renderer gave no slot looks nothing up";
    deep.shadows.lights[0].slot = 0;
    ShadingFeatures deepLookup = only({ShadingFeature::Shade, ShadingFeature::DeepOpacity});
    deepLookup.setShadowLayers(deep.shadows.layers);
    EXPECT_EQ(featuresOf(deep), deepLookup);
    deep.shadows.meshesCast = true;
    EXPECT_EQ(featuresOf(deep), deepLookup) << "meshes cast, but this light has no view of them";
    deep.shadows.lights[0].meshView = deep.shadows.lights[0].view;
    deepLookup.add(ShadingFeature::MeshOccluders);
    EXPECT_EQ(featuresOf(deep), deepLookup);
    deep.shadows.bilinear = true;
    deepLookup.add(ShadingFeature::BilinearShadows);
    EXPECT_EQ(featuresOf(deep), deepLookup);

    FrameRecipe volume = litPlan();
    volume.shadows.mode = ShadowMode::DeepOpacity;
    volume.shadows.bilinear = false;
    castFrom(volume, 0, -1);
    volume.shadows.lights[0].view.valid = false;  // no map's view holds the hair
    volume.shadows.lights[0].byVolume = true;
    EXPECT_EQ(featuresOf(volume), shade) << "a light through the volume, but no grid planned";
    volume.shadows.volumeGrid = fitDensityGrid(glm::dvec3(-1.0), glm::dvec3(1.0), 1000);
    EXPECT_EQ(featuresOf(volume), only({ShadingFeature::Shade, ShadingFeature::DensityVolume}));
    // Dual scattering's local term from the volume: only with a material
    // where dual scattering runs.
    volume.shadows.volumeBackScattering = true;
    EXPECT_EQ(featuresOf(volume), only({ShadingFeature::Shade, ShadingFeature::DensityVolume}));
    const ShadingFeatures dual = only({ShadingFeature::DualScattering});
    EXPECT_EQ(batchShadingFeatures(volume, 0, dual),
              only({ShadingFeature::Shade, ShadingFeature::DualScattering, ShadingFeature::DensityVolume,
                    ShadingFeature::VolumeBackScattering}));
    volume.shadows.volumeGrid = DensityGridShape();
    EXPECT_FALSE(batchShadingFeatures(volume, 0, dual).has(ShadingFeature::VolumeBackScattering)) << "no grid planned";

    FrameRecipe reference = litPlan();
    reference.shadows.mode = ShadowMode::Reference;
    reference.shadows.bilinear = false;
    castFrom(reference, 0);
    EXPECT_EQ(featuresOf(reference), only({ShadingFeature::Shade, ShadingFeature::ShadowReference}));
    FrameRecipe off = litPlan();  // a map, but shadows off
    castFrom(off, 0);
    EXPECT_EQ(featuresOf(off), shade);

    FrameRecipe taps = lobe;
    taps.shadows.mode = ShadowMode::DeepOpacity;
    taps.shadows.bilinear = false;
    castFrom(taps, 0, 3);
    ShadingFeatures tapsLookup =
        only({ShadingFeature::Shade, ShadingFeature::SrbfLights, ShadingFeature::DeepOpacity, ShadingFeature::SrbfShadowTaps});
    tapsLookup.setShadowLayers(taps.shadows.layers);
    EXPECT_EQ(featuresOf(taps), tapsLookup);
    FrameRecipe mipmap = taps;
    mipmap.shadows.convolvedOpacity = true;
    ShadingFeatures mipmapLookup = only(
        {ShadingFeature::Shade, ShadingFeature::SrbfLights, ShadingFeature::DeepOpacity, ShadingFeature::SrbfShadowMipmap});
    mipmapLookup.setShadowLayers(taps.shadows.layers);
    EXPECT_EQ(featuresOf(mipmap), mipmapLookup);
    // An SRBF light without a map of its own reads the one it shares.
    FrameRecipe shared = litPlan(2);
    shared.lighting.lights.lights[1].srbfBandwidth = 8.0f;
    shared.shadows.mode = ShadowMode::DeepOpacity;
    shared.shadows.bilinear = false;
    castFrom(shared, 0);
    shared.shadows.sharedMaps[1] = 0;
    EXPECT_TRUE(featuresOf(shared).has(ShadingFeature::SrbfShadowTaps));
}

// The plan's layer count is compiled in where a deep opacity map is read.
TEST(StrandShadingFeatures, TheLayerCountComesFromThePlan) {
    FrameRecipe deep = litPlan();
    deep.shadows.mode = ShadowMode::DeepOpacity;
    deep.shadows.layers = 7;
    castFrom(deep, 0);
    EXPECT_EQ(featuresOf(deep).shadowLayers(), 7);
    deep.shadows.mode = ShadowMode::Reference;  // the fragment lists have no layers
    EXPECT_EQ(featuresOf(deep).shadowLayers(), 0);
}

// Vertex shadows look up the batch's lights up to the last with a deep
// opacity map.
TEST(StrandShadingFeatures, VertexShadowsReachTheLastLightWithAMap) {
    FrameRecipe six = litPlan(6);
    six.shadows.mode = ShadowMode::DeepOpacity;
    castFrom(six, 1);
    castFrom(six, 4, 1);
    EXPECT_EQ(batchVertexShadowLights(six, 0), 5);
    FrameRecipe none = litPlan();
    none.shadows.mode = ShadowMode::DeepOpacity;
    castFrom(none, 0, -1);
    EXPECT_EQ(batchVertexShadowLights(none, 0), 0);
    FrameRecipe reference = six;  // the reference is looked up per fragment
    reference.shadows.mode = ShadowMode::Reference;
    EXPECT_EQ(batchVertexShadowLights(reference, 0), 0);
    FrameRecipe second = six;  // counted within the batch
    second.lighting.batches = {{0, 4}, {4, 6}};
    EXPECT_EQ(batchVertexShadowLights(second, 0), 2);
    EXPECT_EQ(batchVertexShadowLights(second, 1), 1);
}
