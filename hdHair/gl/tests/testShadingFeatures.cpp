// The strand shading's feature sets (hdHair/gl/ShadingFeatures.h): the
// switches are those shaders/include/shadingFeatures.glsl defines, the layer
// count and vertex shadows make programs of their own, and every program
// one switch short of all, or with one switch alone, compiles and links.
// That the programs draw what the complete one draws is testenv's
// testShaderSpecialization; which features a frame's materials and draws
// reach is render's testStrandShadingFeatures.

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
#include "hdHair/gl/tests/ShadingFeatureSets.h"

using namespace hdhair::gl;

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

// Where a deep opacity map is read, its layer count is compiled in: a
// program of its own per count, named in the stats.
TEST(ShadingFeatures, ADeepOpacityLookupCompilesItsLayerCountIn) {
    ShadingFeatures three = only({ShadingFeature::Shade, ShadingFeature::DeepOpacity, ShadingFeature::BilinearShadows});
    three.setShadowLayers(3);
    EXPECT_EQ(three.shadowLayers(), 3);
    EXPECT_NE(three.glsl().find("#define HDHAIR_SHADOW_LAYERS 3\n"), std::string::npos);
    EXPECT_EQ(three.describe(), "shade deepOpacity bilinearShadows shadowLayers=3");
    ShadingFeatures seven = three;
    seven.setShadowLayers(7);
    EXPECT_NE(seven, three);
    EXPECT_NE(seven.key(), three.key());
    EXPECT_EQ(ShadingFeatures::all().glsl().find("HDHAIR_SHADOW_LAYERS"), std::string::npos);
}

// Vertex shadows (shadowSampling) are a program of their own per count of
// lights looked up, named in the stats.
TEST(ShadingFeatures, VertexShadowsAreAProgramOfTheirOwn) {
    ShadingFeatures perFragment = only({ShadingFeature::Shade, ShadingFeature::DeepOpacity, ShadingFeature::BilinearShadows});
    perFragment.setShadowLayers(3);
    ShadingFeatures perPoint = perFragment;
    perPoint.setVertexShadowLights(1);
    EXPECT_NE(perPoint.key(), perFragment.key());
    EXPECT_NE(perPoint.key(), ShadingFeatures(perFragment).setVertexShadowLights(2).key());
    EXPECT_NE(perPoint.glsl().find("#define HDHAIR_VERTEX_SHADOWS 1\n"), std::string::npos);
    EXPECT_EQ(perFragment.glsl().find("HDHAIR_VERTEX_SHADOWS"), std::string::npos);
    EXPECT_EQ(ShadingFeatures::all().glsl().find("HDHAIR_VERTEX_SHADOWS"), std::string::npos);
    EXPECT_EQ(perPoint.describe(), "shade deepOpacity bilinearShadows shadowLayers=3 vertexShadows=1");
    ShadingFeatures five = perFragment;
    five.setVertexShadowLights(5);
    EXPECT_NE(five.glsl().find("#define HDHAIR_VERTEX_SHADOW_VECTORS 2\n"), std::string::npos);
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
        // The compute rasteriser shades through the same includes; what is
        // its own is the vertex shadows it interpolates. Compute programs
        // compile eagerly on llvmpipe (about a second each), so these sets
        // rather than all of the above.
        const std::vector<ShadingFeatures> computeSets{
            ShadingFeatures(),
            ShadingFeatures::all(),
            only({ShadingFeature::Shade, ShadingFeature::KajiyaKay, ShadingFeature::DeepOpacity,
                  ShadingFeature::BilinearShadows})
                .setShadowLayers(3)
                .setVertexShadowLights(1),
            ShadingFeatures::all().setVertexShadowLights(5),
            ShadingFeatures::all().setVertexShadowLights(16)};
        ShadingPrograms compute({"strandRaster.comp"});
        for (const ShadingFeatures& features : computeSets)
            EXPECT_NO_THROW(compute.get(features)) << "strandRaster.comp with " << features.describe();
        EXPECT_EQ(compute.compiled(), computeSets.size());
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
