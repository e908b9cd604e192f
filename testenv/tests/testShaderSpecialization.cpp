// Specialised strand programs (hdHair/gl/ShadingFeatures.h): a program that
// compiles only the shading its draw can reach draws exactly what the
// complete program draws (specializeShaders=false; both with vertex shadows
// where the frame takes them), colour, depth and ids bit for bit, on stages that between them reach every feature; and every
// feature is reached by one of them, so none goes unchecked.

#include <ostream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "StageRendering.h"
#include "hdHair/gl/ShadingFeatures.h"

using namespace hdhair;
using namespace hdhair::testenv;

namespace {

struct SpecializationCase {
    std::string name;
    std::string stage;  // from the source tree
    std::vector<std::string> settings;
    bool texturedDome = false;  // lit by examples/dome_sky.exr as well
};

// Failures name the case, not its bytes.
void PrintTo(const SpecializationCase& testCase, std::ostream* out) { *out << testCase.name; }

std::vector<SpecializationCase> specializationCases() {
    const std::string shadowed = "testenv/cases/lights_1_shadows_on/stage.usda";
    const std::string domeLit = "examples/dome_lit_strands.usda";
    return {
        {"KajiyaKayWithDeepOpacity", shadowed, {"shadowMapResolution=128"}},
        {"NearestDeepOpacity", shadowed, {"shadowFilter=nearest", "shadowMapResolution=128"}},
        {"DeepOpacityPerFragment", shadowed, {"shadowSampling=fragment", "shadowMapResolution=128"}},
        // Vertex shadows: the lookups in strand.tese, for a light and for SRBF lobes in batches.
        {"VertexShadows", shadowed, {"shadowSampling=vertex", "shadowMapResolution=128"}},
        {"VertexShadowsUnderSrbfLobes", domeLit, {"shadowSampling=vertex", "shadowMapResolution=128"}},
        // The layer count compiled in: one vec4 (1 to 4 layers) and arrays of them.
        {"OneShadowLayer", shadowed, {"shadowLayers=1", "shadowMapResolution=128"}},
        {"SevenShadowLayers", shadowed, {"shadowLayers=7", "shadowMapResolution=128"}},
        {"SevenLayersUnderSrbfLobes", domeLit, {"shadowLayers=7", "shadowMapResolution=128"}},
        {"ReferenceShadows", shadowed, {"shadowMode=reference", "shadowMapResolution=128"}},
        {"LocalLightsInBatchesUnderAnAmbientDome", "testenv/cases/lights_9/stage.usda",
         {"domeLighting=ambient", "shadowMapResolution=128"}},
        {"LocalLightsUnderTheUniformDome", "testenv/cases/lights_9/stage.usda",
         {"domeLighting=srbf", "shadowMapResolution=128"}},
        {"SrbfLobesThroughTheMipChain", domeLit, {"shadowMapResolution=128"}},
        {"SrbfLobesThroughNineTaps", domeLit, {"domeShadowFilter=taps", "shadowMapResolution=128"}},
        {"MarschnerUnderSrbfLobes", domeLit, {"shadingModel=marschner", "shadowMapResolution=128"}},
        {"FlatKajiyaKayAndMarschnerMaterials", "testenv/stages/materials.usda", {}},
        {"MarschnerEvaluatedPerFragment", "examples/wavy_strands.usda",
         {"shadingModel=marschner", "marschner:azimuthal=analytic"}},
        {"PerPointParametersAndAbsorptionUnderADome", "testenv/stages/hair_parameters.usda",
         {"shadowMapResolution=128"}, true},
        {"MeshesOccludeTheLights", "testenv/stages/meshes.usda", {"shadowMapResolution=128"}},
        // The density volume: every light through it, on strands and on meshes.
        {"DensityVolumeShadows", shadowed, {"shadowMode=volume"}},
        {"DensityVolumeOnMeshes", "testenv/stages/meshes.usda", {"shadowMode=volume", "shadowMapResolution=128"}},
        // Dual scattering, its local term from the volume: under a light
        // with a map, under SRBF lobes through the volume's cones, and under
        // the uniform dome.
        {"DualScatteringsLocalTermFromTheVolume", shadowed,
         {"shadingModel=marschner", "multipleScattering=dualScattering", "shadowMapResolution=128"}},
        {"SrbfLobesThroughTheVolumeWithDualScattering", domeLit,
         {"shadingModel=marschner", "multipleScattering=dualScattering", "shadowMode=volume"}},
        {"DualScatteringUnderTheUniformDome", "testenv/cases/lights_9/stage.usda",
         {"shadingModel=marschner", "multipleScattering=dualScattering", "domeLighting=srbf",
          "shadowMapResolution=128"}},
        {"ExactTransparency", "examples/dense_clump.usda", {"transparency=exact", "strandRaster=hardware"}},
        // Lists no longer than 180 fragments a pixel: longer ones sum their
        // tail in the order fragments were appended, which compute
        // workgroups do not fix (docs/transparency.md).
        {"ComputeRaster", "examples/wavy_strands.usda", {"strandRaster=compute"}},
    };
}

// The case's stage rendered with specializeShaders as `specialize` says,
// with ids.
RenderResult renderCase(const SpecializationCase& testCase, bool specialize) {
    StageRenderRequest request;
    request.stagePath = sourcePath(testCase.stage);
    request.imageWidth = 64;
    request.settings = testCase.settings;
    Diagnostics diagnostics;
    Scene scene = readStage(request, diagnostics);
    if (testCase.texturedDome) {
        LightPrim dome;
        dome.path = "/World/testDome";
        dome.type = LightType::Dome;
        dome.textureFile = sourcePath("examples/dome_sky.exr");
        dome.textureFormat = "latlong";
        dome.intensity = 0.3f;
        scene.setLight(dome);
    }
    Renderer& renderer = sharedRenderer();
    const CameraView camera = stageCamera(scene, request, renderer, diagnostics);
    RenderSettings settings = stageSettings(request);
    settings.set("specializeShaders", specialize ? "true" : "false");
    return renderer.render(scene, camera, settings, diagnostics, RenderOutputs{true});
}

class ShaderSpecialization : public ::testing::TestWithParam<SpecializationCase> {};

TEST_P(ShaderSpecialization, DrawsWhatTheCompleteProgramDraws) {
    const RenderResult specialized = renderCase(GetParam(), true);
    const RenderResult complete = renderCase(GetParam(), false);
    ASSERT_GT(coverage(specialized.color), 0.01);
    // Every part, whatever the draw; vertex shadows as the frame asks for them.
    ASSERT_FALSE(complete.stats.strandShaders.empty());
    for (const std::string& program : complete.stats.strandShaders)
        EXPECT_EQ(program.rfind(gl::ShadingFeatures::all().describe(), 0), 0u) << program;
    EXPECT_NE(specialized.stats.strandShaders, complete.stats.strandShaders);
    EXPECT_EQ(specialized.color.pixels, complete.color.pixels);
    EXPECT_EQ(specialized.depth.pixels, complete.depth.pixels);
    EXPECT_EQ(specialized.primIds, complete.primIds);
    EXPECT_EQ(specialized.instanceIds, complete.instanceIds);
    EXPECT_EQ(specialized.elementIds, complete.elementIds);
}

std::string caseName(const ::testing::TestParamInfo<SpecializationCase>& info) { return info.param.name; }

INSTANTIATE_TEST_SUITE_P(Stages, ShaderSpecialization, ::testing::ValuesIn(specializationCases()), caseName);

TEST(ShaderSpecializationCoverage, TheStagesReachEveryFeature) {
    // The features the specialised programs of all the cases compiled, from
    // the frames' own account of them (RenderStats::strandShaders).
    std::set<std::string> reached;
    for (const SpecializationCase& testCase : specializationCases()) {
        for (const std::string& program : renderCase(testCase, true).stats.strandShaders) {
            std::istringstream names(program);
            for (std::string name; names >> name;) reached.insert(name);
        }
    }
    for (const gl::ShadingFeatureSwitch& entry : gl::shadingFeatureSwitches())
        EXPECT_TRUE(reached.count(entry.name)) << entry.name << " is reached by no stage of the test";
}

}  // namespace
