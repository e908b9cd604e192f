// Which parts of the strand shading a draw reaches (hdHair/gl/ShadingFeatures.h):
// each uniform and material condition turns on its feature and nothing
// else, the switches are those shaders/include/shadingFeatures.glsl
// defines, and every program one switch short of all, or with one switch
// alone, compiles and links. That the programs draw what the complete one
// draws is testenv's testShaderSpecialization.

#include <ostream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "hdHair/gl/GlRenderThread.h"
#include "hdHair/gl/ShaderSources.h"
#include "hdHair/gl/ShadingFeatures.h"
#include "hdHair/gl/ShadingPrograms.h"

using namespace hdhair::gl;

namespace hdhair::gl {
// Failures name the features, not the bytes.
void PrintTo(const ShadingFeatures& features, std::ostream* out) { *out << features.describe(); }
}  // namespace hdhair::gl

namespace {

ShadingFeatures only(std::initializer_list<ShadingFeature> features) {
    ShadingFeatures set;
    for (ShadingFeature feature : features) set.add(feature);
    return set;
}

// A colour draw of distant lights without shadows or materials' needs.
struct Draw {
    FrameUniforms frame;
    LightUniforms lights;
    ShadowUniforms shadows;
    Draw() {
        frame.drawMode = 1;
        lights.lightCount.x = 1;
        shadows.lightMap[0].x = -1.0f;
    }
    ShadingFeatures features(ShadingFeatures materials = {}) const {
        return strandShadingFeatures(frame, lights, shadows, materials);
    }
};

GpuHairMaterial material(int model, int flags = 0) {
    GpuHairMaterial entry;
    entry.modelAndLayer = glm::ivec4(model, 0, flags, 0);
    return entry;
}

}  // namespace

TEST(ShadingFeatures, TheSwitchesAreThoseTheShaderFileDefines) {
    const std::string file = embeddedShaderSources().at("include/shadingFeatures.glsl");
    std::set<std::string> defined;
    const std::regex define(R"(#define (HDHAIR_FEATURE_[A-Z_]+) 1\b)");
    for (auto it = std::sregex_iterator(file.begin(), file.end(), define); it != std::sregex_iterator(); ++it)
        defined.insert((*it)[1]);
    std::set<std::string> switches;
    for (const ShadingFeatureSwitch& entry : shadingFeatureSwitches()) switches.insert(entry.macro);
    EXPECT_EQ(defined, switches);
    // The replacement defines every switch, 1 or 0.
    const std::string text = only({ShadingFeature::Shade, ShadingFeature::DeepOpacity}).glsl();
    for (const ShadingFeatureSwitch& entry : shadingFeatureSwitches()) {
        const bool on = entry.feature == ShadingFeature::Shade || entry.feature == ShadingFeature::DeepOpacity;
        EXPECT_NE(text.find(std::string("#define ") + entry.macro + (on ? " 1\n" : " 0\n")), std::string::npos)
            << entry.macro;
    }
    EXPECT_EQ(only({ShadingFeature::Shade, ShadingFeature::DeepOpacity}).describe(), "shade deepOpacity");
    EXPECT_EQ(ShadingFeatures().describe(), "none");
}

TEST(ShadingFeatures, MaterialsCallForTheirModelsAndFlags) {
    EXPECT_EQ(materialShadingFeatures({}), ShadingFeatures());
    EXPECT_EQ(materialShadingFeatures({material(0)}), ShadingFeatures());  // flat: nothing to compile
    EXPECT_EQ(materialShadingFeatures({material(1)}), only({ShadingFeature::KajiyaKay}));
    EXPECT_EQ(materialShadingFeatures({material(2)}), only({ShadingFeature::MarschnerTabled}));
    EXPECT_EQ(materialShadingFeatures({material(2, kHairMaterialAnalytic)}), only({ShadingFeature::MarschnerAnalytic}));
    EXPECT_EQ(materialShadingFeatures({material(1, kHairMaterialPerPoint)}),
              only({ShadingFeature::KajiyaKay, ShadingFeature::PerPointParameters}));
    EXPECT_EQ(materialShadingFeatures({material(2, kHairMaterialSrbfLobes)}),
              only({ShadingFeature::MarschnerTabled, ShadingFeature::SrbfAbsorption}));
    // Absorption per fragment is Marschner's only (srbfAbsorption's test).
    EXPECT_EQ(materialShadingFeatures({material(1, kHairMaterialSrbfLobes)}), only({ShadingFeature::KajiyaKay}));
    EXPECT_EQ(materialShadingFeatures({material(0), material(1), material(2)}),
              only({ShadingFeature::KajiyaKay, ShadingFeature::MarschnerTabled}));
}

TEST(ShadingFeatures, EachUniformConditionTurnsOnItsFeature) {
    const ShadingFeatures shade = only({ShadingFeature::Shade});
    Draw draw;
    EXPECT_EQ(draw.features(), shade);
    EXPECT_EQ(draw.features(only({ShadingFeature::KajiyaKay})), only({ShadingFeature::Shade, ShadingFeature::KajiyaKay}));

    Draw ids;  // the ids pass shades nothing, whatever else it binds
    ids.frame.drawMode = 2;
    ids.lights.ambient.w = 1.0f;
    EXPECT_EQ(ids.features(ShadingFeatures::all()), ShadingFeatures());

    Draw dome;
    dome.lights.ambient.w = 1.0f;
    EXPECT_EQ(dome.features(), only({ShadingFeature::Shade, ShadingFeature::UniformDome}));

    Draw local;
    local.lights.lightVector[0].w = 1.0f;
    EXPECT_EQ(local.features(), only({ShadingFeature::Shade, ShadingFeature::LocalLights}));
    Draw lobe;
    lobe.lights.lightVector[0].w = 2.0f;
    EXPECT_EQ(lobe.features(), only({ShadingFeature::Shade, ShadingFeature::SrbfLights}));
    // Lights past the pass's count are not read.
    Draw unused;
    unused.lights.lightVector[1].w = 2.0f;
    EXPECT_EQ(unused.features(), shade);

    Draw deep;
    deep.shadows.mode.x = kShadowModeDeepOpacity;
    EXPECT_EQ(deep.features(), shade) << "a mode with no light that has a map looks nothing up";
    deep.shadows.lightMap[0].x = 0.0f;
    EXPECT_EQ(deep.features(), only({ShadingFeature::Shade, ShadingFeature::DeepOpacity}));
    deep.shadows.occluders.x = 1;
    EXPECT_EQ(deep.features(), only({ShadingFeature::Shade, ShadingFeature::DeepOpacity, ShadingFeature::MeshOccluders}));
    deep.shadows.mode.z = 1;  // shadowFilter=bilinear
    EXPECT_EQ(deep.features(), only({ShadingFeature::Shade, ShadingFeature::DeepOpacity, ShadingFeature::MeshOccluders,
                                     ShadingFeature::BilinearShadows}));

    Draw reference;
    reference.shadows.mode.x = kShadowModeReference;
    reference.shadows.lightMap[0].x = 0.0f;
    EXPECT_EQ(reference.features(), only({ShadingFeature::Shade, ShadingFeature::ShadowReference}));
    Draw off;
    off.shadows.lightMap[0].x = 0.0f;  // a map, but shadows off
    EXPECT_EQ(off.features(), shade);

    Draw taps = lobe;
    taps.shadows.mode.x = kShadowModeDeepOpacity;
    taps.shadows.lightMap[0].x = 3.0f;
    EXPECT_EQ(taps.features(), only({ShadingFeature::Shade, ShadingFeature::SrbfLights, ShadingFeature::DeepOpacity,
                                     ShadingFeature::SrbfShadowTaps}));
    Draw mipmap = taps;
    mipmap.shadows.occluders.y = 1;
    EXPECT_EQ(mipmap.features(), only({ShadingFeature::Shade, ShadingFeature::SrbfLights,
                                       ShadingFeature::DeepOpacity, ShadingFeature::SrbfShadowMipmap}));
}

// Where a deep opacity map is read, its layer count is compiled in: a
// program of its own per count, named in the stats.
TEST(ShadingFeatures, ADeepOpacityLookupCompilesItsLayerCountIn) {
    Draw deep;
    deep.shadows.mode = glm::ivec4(kShadowModeDeepOpacity, 3, 1, 512);
    deep.shadows.lightMap[0].x = 0.0f;
    const ShadingFeatures three = deep.features();
    EXPECT_EQ(three.shadowLayers(), 3);
    EXPECT_NE(three.glsl().find("#define HDHAIR_SHADOW_LAYERS 3\n"), std::string::npos);
    EXPECT_EQ(three.describe(), "shade deepOpacity bilinearShadows shadowLayers=3");
    deep.shadows.mode.y = 7;
    EXPECT_NE(deep.features(), three);
    EXPECT_NE(deep.features().key(), three.key());

    Draw reference = deep;  // the fragment lists have no layers
    reference.shadows.mode.x = kShadowModeReference;
    EXPECT_EQ(reference.features().shadowLayers(), 0);
    Draw off = deep;
    off.shadows.mode.x = kShadowModeOff;
    EXPECT_EQ(off.features().shadowLayers(), 0);
    EXPECT_EQ(ShadingFeatures::all().glsl().find("HDHAIR_SHADOW_LAYERS"), std::string::npos);
}

// Vertex shadows (shadowSampling=vertex) are asked for by the frame, not
// read from the uniforms: a program of their own per count of lights looked
// up (to the last with a deep opacity map), named in the stats.
TEST(ShadingFeatures, VertexShadowsAreAProgramOfTheirOwn) {
    Draw deep;
    deep.shadows.mode = glm::ivec4(kShadowModeDeepOpacity, 3, 1, 512);
    deep.shadows.lightMap[0].x = 0.0f;
    EXPECT_EQ(vertexShadowLights(deep.lights, deep.shadows), 1);
    const ShadingFeatures perFragment = deep.features();
    ShadingFeatures perPoint = perFragment;
    perPoint.setVertexShadowLights(1);
    EXPECT_NE(perPoint.key(), perFragment.key());
    EXPECT_NE(perPoint.key(), ShadingFeatures(perFragment).setVertexShadowLights(2).key());
    EXPECT_NE(perPoint.glsl().find("#define HDHAIR_VERTEX_SHADOWS 1\n"), std::string::npos);
    EXPECT_EQ(perFragment.glsl().find("HDHAIR_VERTEX_SHADOWS"), std::string::npos);
    EXPECT_EQ(ShadingFeatures::all().glsl().find("HDHAIR_VERTEX_SHADOWS"), std::string::npos);
    EXPECT_EQ(perPoint.describe(), "shade deepOpacity bilinearShadows shadowLayers=3 vertexShadows=1");

    Draw six;  // six lights, the fifth (index 4) the last with a map
    six.shadows.mode = deep.shadows.mode;
    six.lights.lightCount.x = 6;
    for (glm::vec4& map : six.shadows.lightMap) map.x = -1.0f;
    six.shadows.lightMap[1].x = 0.0f;
    six.shadows.lightMap[4].x = 1.0f;
    EXPECT_EQ(vertexShadowLights(six.lights, six.shadows), 5);
    ShadingFeatures five = perFragment;
    five.setVertexShadowLights(5);
    EXPECT_NE(five.glsl().find("#define HDHAIR_VERTEX_SHADOW_VECTORS 2\n"), std::string::npos);
    Draw none = deep;  // no light with a map: nothing to look up
    none.shadows.lightMap[0].x = -1.0f;
    EXPECT_EQ(vertexShadowLights(none.lights, none.shadows), 0);
    Draw reference = deep;  // the reference is looked up per fragment
    reference.shadows.mode.x = kShadowModeReference;
    EXPECT_EQ(vertexShadowLights(reference.lights, reference.shadows), 0);
}

TEST(ShadingFeatures, EveryProgramOneSwitchFromAllOrWithOneAloneCompiles) {
    GlRenderThread thread(GlBackend::Egl);
    thread.run([] {
        std::vector<ShadingFeatures> sets{ShadingFeatures(), ShadingFeatures::all()};
        for (const ShadingFeatureSwitch& entry : shadingFeatureSwitches()) {
            ShadingFeatures allBut;
            for (const ShadingFeatureSwitch& other : shadingFeatureSwitches())
                if (other.feature != entry.feature) allBut.add(other.feature);
            sets.push_back(allBut);
            sets.push_back(only({ShadingFeature::Shade, entry.feature}));
        }
        // Layer counts compiled in: one vec4, its edges, and arrays of them.
        for (int layers : {1, 2, 3, 4, 5, 8, 32}) {
            sets.push_back(ShadingFeatures::all().setShadowLayers(layers));
            sets.push_back(only({ShadingFeature::Shade, ShadingFeature::KajiyaKay, ShadingFeature::DeepOpacity,
                                 ShadingFeature::BilinearShadows})
                               .setShadowLayers(layers));
        }
        // Vertex shadows for 1 to 16 lights, over every part and over one light's.
        for (int lights : {1, 2, 3, 4, 5, 8, 9, 16}) {
            sets.push_back(ShadingFeatures::all().setVertexShadowLights(lights));
            sets.push_back(only({ShadingFeature::Shade, ShadingFeature::KajiyaKay, ShadingFeature::DeepOpacity,
                                 ShadingFeature::BilinearShadows})
                               .setShadowLayers(3)
                               .setVertexShadowLights(lights));
        }
        for (const char* fragment : {"strand.frag", "strandFragmentList.frag"}) {
            ShadingPrograms programs({"strand.vert", "strand.tesc", "strand.tese", "strand.geom", fragment});
            for (const ShadingFeatures& features : sets)
                EXPECT_NO_THROW(programs.get(features)) << fragment << " with " << features.describe();
            EXPECT_EQ(programs.compiled(), sets.size());
        }
    });
}

// Strand lines: the light views' programs (and the camera's, which could
// take them) without strand.geom, the evaluation shader feeding the
// fragment stage; with vertex shadows, which only the camera reads, a
// compile error that says so.
TEST(ShadingFeatures, StrandLinesCompileWithoutTheGeometryShader) {
    EXPECT_EQ(ShadingFeatures::all().glsl().find("HDHAIR_STRAND_LINES"), std::string::npos);
    const ShadingFeatures lines = ShadingFeatures::all().setStrandLines(true);
    EXPECT_NE(lines.glsl().find("#define HDHAIR_STRAND_LINES 1\n"), std::string::npos);
    EXPECT_NE(lines.key(), ShadingFeatures::all().key());
    EXPECT_NE(lines.describe().find("strandLines"), std::string::npos);
    GlRenderThread thread(GlBackend::Egl);
    thread.run([&] {
        for (const char* fragment : {"shadowDepth.frag", "deepOpacity.frag", "strand.frag", "strandFragmentList.frag"}) {
            ShadingPrograms programs({"strand.vert", "strand.tesc", "strand.tese", "strand.geom", fragment});
            EXPECT_NO_THROW(programs.get(lines)) << fragment;
            EXPECT_NO_THROW(programs.get(ShadingFeatures::all().setShadowLayers(3).setStrandLines(true))) << fragment;
            EXPECT_EQ(programs.compiled(), 2u);
        }
        ShadingPrograms camera({"strand.vert", "strand.tesc", "strand.tese", "strand.geom", "strand.frag"});
        try {
            camera.get(ShadingFeatures::all().setVertexShadowLights(1).setStrandLines(true));
            ADD_FAILURE() << "strand lines with vertex shadows compiled";
        } catch (const std::runtime_error& error) {
            EXPECT_NE(std::string(error.what()).find("strand lines are for the light views"), std::string::npos)
                << error.what();
        }
    });
}
