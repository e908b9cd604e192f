// The frame graph decides what runs: wanted passes whose output something
// downstream reads, in declaration order; wiring mistakes are caught.

#include <stdexcept>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hdHair/render/FrameGraph.h"

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
    graph.input("strands");
    graph.add(pass("shadow", {"strands"}, {"shadowMap"}));
    graph.add(pass("clear", {}, {"color"}));
    std::vector<FrameResource> reads{"strands", "color"};
    if (colourReadsShadow) reads.push_back("shadowMap");
    graph.add(pass("color", reads, {"color"}));
    graph.add(pass("readback", {"color"}, {"image"}));
    graph.output("image");
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
    EXPECT_NE(text.find("not built: nothing reads its output (shadowMap)"), std::string::npos) << text;
}

TEST(FrameGraph, PassesThatAreNotWantedNeverRun) {
    FrameGraph graph;
    graph.add(pass("clear", {}, {"color"}));
    graph.add(pass("extra", {"color"}, {"color"}, false));
    graph.add(pass("readback", {"color"}, {"image"}));
    graph.output("image");
    graph.compile();
    EXPECT_FALSE(graph.isEnabled("extra"));
    EXPECT_TRUE(graph.isEnabled("clear"));
    EXPECT_EQ(graph.find("extra")->reason, "because extra");  // no "not built" note: it was never wanted
    EXPECT_EQ(graph.describe().find("not built"), std::string::npos);
}

TEST(FrameGraph, InPlaceUpdatesKeepTheirProducersAlive) {
    // clear -> batch 1 -> batch 2 all write "color"; each later one reads it.
    FrameGraph graph;
    graph.add(pass("clear", {}, {"color"}));
    graph.add(pass("batch1", {"color"}, {"color"}));
    graph.add(pass("batch2", {"color"}, {"color"}));
    graph.add(pass("readback", {"color"}, {"image"}));
    graph.output("image");
    graph.compile();
    for (const char* name : {"clear", "batch1", "batch2", "readback"}) EXPECT_TRUE(graph.isEnabled(name)) << name;
}

TEST(FrameGraph, AnOverwrittenResultIsNotBuilt) {
    // "draft" writes colour that "final" replaces without reading: draft is dead.
    FrameGraph graph;
    graph.add(pass("draft", {}, {"color"}));
    graph.add(pass("final", {}, {"color"}));
    graph.add(pass("readback", {"color"}, {"image"}));
    graph.output("image");
    graph.compile();
    EXPECT_FALSE(graph.isEnabled("draft"));
    EXPECT_TRUE(graph.isEnabled("final"));
}

TEST(FrameGraph, ReadingWhatNothingWroteIsAWiringError) {
    FrameGraph graph;
    graph.add(pass("color", {"strands"}, {"color"}));
    graph.add(pass("readback", {"color"}, {"image"}));
    graph.output("image");
    EXPECT_THROW(graph.compile(), std::logic_error);
    graph.input("strands");
    EXPECT_NO_THROW(graph.compile());
}

TEST(FrameGraph, StatsKeepEachPassWithItsResourcesAndTime) {
    FrameGraph graph = shadowedFrame(true);
    nlohmann::json json = graph.toJson({0.0, 0.0, 2.5, 0.0});
    ASSERT_EQ(json.size(), 4u);
    EXPECT_EQ(json[2]["pass"], "color");
    EXPECT_EQ(json[2]["reads"], nlohmann::json({"strands", "color", "shadowMap"}));
    EXPECT_EQ(json[2]["writes"], nlohmann::json({"color"}));
    EXPECT_EQ(json[2]["milliseconds"], 2.5);
    EXPECT_EQ(json[2]["enabled"], true);
}
