// The frame graph decides what runs: wanted passes whose output something
// downstream reads, in declaration order; wiring mistakes are caught.

#include <stdexcept>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hdHair/plan/FrameGraph.h"

using namespace hdhair;

namespace {

FramePass pass(const char* name, std::vector<FrameResource> reads, std::vector<FrameResource> writes,
               bool wanted = true) {
    // The graph decides by reads and writes alone; the kind is the renderer's.
    return FramePass{PassKind::Strands, name, std::move(reads), std::move(writes), wanted,
                     std::string("because ") + name};
}

// A small frame: shadows feed the colour pass only when it reads them.
FrameGraph shadowedFrame(bool colourReadsShadow) {
    FrameGraph graph;
    graph.nameLights({"/key"});
    graph.input(ResourceKind::Strands);
    graph.add(pass("shadow", {ResourceKind::Strands}, {FrameResource{ResourceKind::DeepOpacity, 0}}));
    graph.add(pass("clear", {}, {ResourceKind::Color}));
    std::vector<FrameResource> reads{ResourceKind::Strands, ResourceKind::Color};
    if (colourReadsShadow) reads.push_back(FrameResource{ResourceKind::DeepOpacity, 0});
    graph.add(pass("color", reads, {ResourceKind::Color}));
    graph.add(pass("readback", {ResourceKind::Color}, {ResourceKind::Aovs}));
    graph.output(ResourceKind::Aovs);
    graph.compile();
    return graph;
}

}  // namespace

TEST(FrameGraph, AWantedPassRunsOnlyWhenSomethingReadsItsOutput) {
    FrameGraph lit = shadowedFrame(true);
    EXPECT_TRUE(lit.isEnabled("shadow"));
    EXPECT_TRUE(lit.isEnabled("color"));

    FrameGraph unlit = shadowedFrame(false);
    EXPECT_FALSE(unlit.isEnabled("shadow"));
    EXPECT_TRUE(unlit.isEnabled("clear"));
    EXPECT_TRUE(unlit.isEnabled("readback"));
    const std::string text = unlit.describe();
    EXPECT_NE(text.find("not built: nothing reads its output (deepOpacity /key)"), std::string::npos) << text;
}

TEST(FrameGraph, PassesThatAreNotWantedNeverRun) {
    FrameGraph graph;
    graph.add(pass("clear", {}, {ResourceKind::Color}));
    graph.add(pass("extra", {ResourceKind::Color}, {ResourceKind::Color}, false));
    graph.add(pass("readback", {ResourceKind::Color}, {ResourceKind::Aovs}));
    graph.output(ResourceKind::Aovs);
    graph.compile();
    EXPECT_FALSE(graph.isEnabled("extra"));
    EXPECT_TRUE(graph.isEnabled("clear"));
    EXPECT_EQ(graph.find("extra")->reason, "because extra");  // no "not built" note: it was never wanted
    EXPECT_EQ(graph.describe().find("not built"), std::string::npos);
}

TEST(FrameGraph, InPlaceUpdatesKeepTheirProducersAlive) {
    // clear -> batch 1 -> batch 2 all write "color"; each later one reads it.
    FrameGraph graph;
    graph.add(pass("clear", {}, {ResourceKind::Color}));
    graph.add(pass("batch1", {ResourceKind::Color}, {ResourceKind::Color}));
    graph.add(pass("batch2", {ResourceKind::Color}, {ResourceKind::Color}));
    graph.add(pass("readback", {ResourceKind::Color}, {ResourceKind::Aovs}));
    graph.output(ResourceKind::Aovs);
    graph.compile();
    for (const char* name : {"clear", "batch1", "batch2", "readback"}) EXPECT_TRUE(graph.isEnabled(name)) << name;
}

TEST(FrameGraph, AnOverwrittenResultIsNotBuilt) {
    // "draft" writes colour that "final" replaces without reading: draft is dead.
    FrameGraph graph;
    graph.add(pass("draft", {}, {ResourceKind::Color}));
    graph.add(pass("final", {}, {ResourceKind::Color}));
    graph.add(pass("readback", {ResourceKind::Color}, {ResourceKind::Aovs}));
    graph.output(ResourceKind::Aovs);
    graph.compile();
    EXPECT_FALSE(graph.isEnabled("draft"));
    EXPECT_TRUE(graph.isEnabled("final"));
}

TEST(FrameGraph, ReadingWhatNothingWroteIsAWiringError) {
    FrameGraph graph;
    graph.add(pass("color", {ResourceKind::Strands}, {ResourceKind::Color}));
    graph.add(pass("readback", {ResourceKind::Color}, {ResourceKind::Aovs}));
    graph.output(ResourceKind::Aovs);
    EXPECT_THROW(graph.compile(), std::logic_error);
    graph.input(ResourceKind::Strands);
    EXPECT_NO_THROW(graph.compile());
}

// A resource is a kind and, for the kinds each light has one of, the light's
// planned shadow: those of two lights are two resources, whatever their names.
TEST(FrameGraph, ResourcesAreKindsAndLights) {
    EXPECT_EQ(FrameResource(ResourceKind::DeepOpacity, 1), FrameResource(ResourceKind::DeepOpacity, 1));
    EXPECT_NE(FrameResource(ResourceKind::DeepOpacity, 1), FrameResource(ResourceKind::DeepOpacity, 2));
    EXPECT_NE(FrameResource(ResourceKind::DeepOpacity, 1), FrameResource(ResourceKind::HairDepth, 1));
    // Kinds of one per frame have no light index.
    EXPECT_EQ(FrameResource(ResourceKind::Color, 3), FrameResource(ResourceKind::Color));
    FrameGraph graph;
    graph.nameLights({"/key", "camera light"});
    EXPECT_EQ(graph.nameOf({ResourceKind::MeshDepth, 1}), "meshDepth camera light");
    EXPECT_EQ(graph.nameOf(ResourceKind::ConvolvedOpacity), "convolvedOpacity");
    // A light the graph was not told of is named by its index.
    EXPECT_EQ(graph.nameOf({ResourceKind::HairDepth, 7}), "hairDepth 7");
}

TEST(FrameGraph, StatsKeepEachPassWithItsResourcesAndTime) {
    FrameGraph graph = shadowedFrame(true);
    nlohmann::json json = graph.toJson({0.0, 0.0, 2.5, 0.0});
    ASSERT_EQ(json.size(), 4u);
    EXPECT_EQ(json[2]["pass"], "color");
    EXPECT_EQ(json[2]["reads"], nlohmann::json({"strands", "color", "deepOpacity /key"}));
    EXPECT_EQ(json[2]["writes"], nlohmann::json({"color"}));
    EXPECT_EQ(json[2]["milliseconds"], 2.5);
    EXPECT_EQ(json[2]["enabled"], true);
}
