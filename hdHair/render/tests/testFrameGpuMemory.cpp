// What --stats reports as the frame's GPU memory (RenderStats::gpuBytes, from
// hdHair/gl/GpuMemory.h) against what the buffers and images must hold,
// worked out here from their layouts: 144 bytes a segment of strand geometry
// (four 32-byte control points, a curve index, a prim and instance pair and a
// material index), 4 a segment of draw order, and per pixel 16 (RGBA32F
// colour) + 4 (depth) + 4 (blended frames' nearest depth) + 12 (ids, when
// asked for). Fresh renderers size their buffers to the frame exactly.

#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/render/Renderer.h"
#include "hdHair/render/tests/SquareCamera.h"
#include "hdHair/scene/Scene.h"

using namespace hdhair;
using hdhair::test::squareCamera;

namespace {

// A control point (32 bytes); per segment where its controls start, its
// curve and its prim's slot; per drawn prim its ids and material.
constexpr uint64_t kControlPointBytes = 32;
constexpr uint64_t kStrandBytesPerSegment = 4 + 4 + 4;
constexpr uint64_t kDrawnPrimBytes = 16;
constexpr uint64_t kOrderBytesPerSegment = 4;

// `curves` horizontal catmullRom strands of `spans` spans each (spans + 3
// points: every span one segment), 0.05 wide, in the plane z = 0.
CurvesPrim strands(const std::string& path, int curves, int spans, float opacity) {
    CurvesPrim prim;
    prim.path = path;
    prim.type = CurveType::Cubic;
    prim.basis = CurveBasis::CatmullRom;
    for (int c = 0; c < curves; ++c) {
        const float y = -0.9f + 1.8f * float(c) / float(std::max(curves - 1, 1));
        prim.curveVertexCounts.push_back(spans + 3);
        for (int i = 0; i < spans + 3; ++i)
            prim.points.push_back({-1.0f + 2.0f * float(i) / float(spans + 2), y, 0.0f});
    }
    prim.primvars["widths"].name = "widths";
    prim.primvars["widths"].values = {0.05f};
    prim.primvars["displayOpacity"].name = "displayOpacity";
    prim.primvars["displayOpacity"].values = {opacity};
    return prim;
}

uint64_t bytesOf(const RenderStats& stats, const std::string& use) {
    auto found = stats.gpuBytes.find(use);
    return found == stats.gpuBytes.end() ? 0 : found->second;
}

RenderStats renderFresh(const Scene& scene, int pixels, const RenderOutputs& outputs = {},
                        const std::vector<std::string>& settings = {}) {
    Renderer renderer(gl::GlBackend::Egl);
    Diagnostics diagnostics;
    return renderer
        .render(scene, squareCamera(pixels), RenderSettings::fromAssignments(Complexity::Low, settings), diagnostics,
                outputs)
        .stats;
}

}  // namespace

TEST(FrameGpuMemory, StrandAndOrderBytesFollowTheSegmentCount) {
    for (int curves : {10, 20, 40}) {
        Scene scene;
        scene.setCurves(strands("/hair", curves, 3, 0.5f));
        // The hardware rasteriser: the bin sort's draw order is on the GPU.
        const RenderStats stats = renderFresh(scene, 64, {}, {"strandRaster=hardware"});
        ASSERT_EQ(stats.segments, uint64_t(curves) * 3);
        ASSERT_EQ(stats.transparency, "binSorted");
        // Catmull-Rom spans share their curve's controls: 6 a curve.
        EXPECT_EQ(bytesOf(stats, "strandGeometry"),
                  kStrandBytesPerSegment * stats.segments + kControlPointBytes * uint64_t(curves) * 6 + kDrawnPrimBytes)
            << curves << " curves";
        EXPECT_EQ(bytesOf(stats, "drawOrder"), kOrderBytesPerSegment * stats.segments) << curves << " curves";
        EXPECT_EQ(stats.authoredPoints, uint64_t(curves) * 6);
    }
}

// The memory goal (docs/performance.md, "Memory"): at most 64 GPU bytes an authored point for a
// groom of Catmull-Rom strands (TressFX assets have 16 or 32 points a strand):
// the strands' geometry and their drawing order together.
TEST(FrameGpuMemory, ACatmullRomGroomTakesAtMost64BytesAnAuthoredPoint) {
    for (int points : {8, 16, 32}) {
        Scene scene;
        scene.setCurves(strands("/hair", 50, points - 3, 0.5f));
        const RenderStats stats = renderFresh(scene, 64, {}, {"strandRaster=hardware"});
        ASSERT_EQ(stats.authoredPoints, 50u * uint64_t(points));
        const uint64_t bytes = bytesOf(stats, "strandGeometry") + bytesOf(stats, "drawOrder");
        EXPECT_EQ(bytes, 50u * (kControlPointBytes * uint64_t(points) +
                                (kStrandBytesPerSegment + kOrderBytesPerSegment) * uint64_t(points - 3)) +
                             kDrawnPrimBytes);
        EXPECT_LE(bytes, 64u * stats.authoredPoints) << points << " points a strand";
        // The same on the CPU beyond the parsed stage: the prepared curves
        // (controls, and per segment its first control and curve), the sort
        // hashes, the span lengths and the frame's draw order.
        const uint64_t segments = 50u * uint64_t(points - 3);
        const auto cpu = [&](const char* use) { return stats.cpuBytes.count(use) ? stats.cpuBytes.at(use) : 0u; };
        EXPECT_EQ(cpu("preparedCurves"), kControlPointBytes * 50u * uint64_t(points) + 8u * segments);
        EXPECT_EQ(cpu("sortHashes"), 2u * segments);
        EXPECT_EQ(cpu("spanLengths"), 4u * segments);
        EXPECT_EQ(cpu("drawOrder"), 4u * segments);
        EXPECT_EQ(cpu("hairParameterPoints"), 0u);
        EXPECT_LE(stats.toJson()["cpuMemory"]["total"].get<uint64_t>(), 64u * stats.authoredPoints);
    }
}

TEST(FrameGpuMemory, TheFrameTargetHoldsWhatTheFrameDelivers) {
    Scene blended, opaque;
    blended.setCurves(strands("/hair", 8, 2, 0.5f));
    opaque.setCurves(strands("/hair", 8, 2, 1.0f));
    EXPECT_EQ(bytesOf(renderFresh(blended, 64), "frameTarget"), 64u * 64u * (16 + 4 + 4));
    const RenderStats solid = renderFresh(opaque, 64, {}, {"transparency=opaque"});
    ASSERT_EQ(solid.transparency, "opaque");
    EXPECT_EQ(bytesOf(solid, "frameTarget"), 64u * 64u * (16 + 4));
    EXPECT_EQ(bytesOf(solid, "drawOrder"), 0u);  // the opaque path draws unsorted
    EXPECT_EQ(bytesOf(renderFresh(blended, 64, RenderOutputs{true}), "frameTarget"), 64u * 64u * (16 + 4 + 4 + 12));
    // 4x multisampled colour and depth, resolved into single-sampled ones.
    const RenderStats msaa = renderFresh(opaque, 64, {}, {"transparency=opaque", "msaaSamples=4"});
    EXPECT_EQ(bytesOf(msaa, "frameTarget"), 64u * 64u * (16 + 4) * (4 + 1));
}

TEST(FrameGpuMemory, TheTotalIsTheSumAndEveryUseIsNamed) {
    Scene scene;
    scene.setCurves(strands("/hair", 12, 4, 0.5f));
    const RenderStats stats = renderFresh(scene, 48);
    uint64_t sum = 0;
    for (const auto& [use, bytes] : stats.gpuBytes) sum += bytes;
    const nlohmann::json json = stats.toJson();
    EXPECT_EQ(json["gpuMemory"]["total"].get<uint64_t>(), sum);
    EXPECT_EQ(json["gpuMemory"]["strandGeometry"].get<uint64_t>(), bytesOf(stats, "strandGeometry"));
    EXPECT_EQ(json["authoredPoints"].get<uint64_t>(), 12u * 7u);
    // Storage nobody named (uniform blocks, one-word placeholder buffers)
    // is the same however many segments and pixels a frame has.
    Scene larger;
    larger.setCurves(strands("/hair", 40, 8, 0.5f));
    EXPECT_EQ(bytesOf(renderFresh(larger, 96), "other"), bytesOf(stats, "other"));
    EXPECT_GT(bytesOf(stats, "other"), 0u);
    // The camera light casts no shadow by default: no map, only the
    // one-texel placeholders the lookups bind (hair depth, layers, mesh depth).
    EXPECT_EQ(bytesOf(stats, "shadowMaps"), 1u * 1u * (4 + 8 + 4));
    // Asked to cast: one slot of 512 x 512 texels, each a nearest hair depth
    // (R32F), one RGBA16F target of 3 layers and a mesh depth (R32F).
    EXPECT_EQ(bytesOf(renderFresh(scene, 48, {}, {"cameraLightShadows=on"}), "shadowMaps"), 512u * 512u * (4 + 8 + 4));
}

TEST(FrameGpuMemory, GrowthReservesHalfAgainAndResizingFreesTheOldTarget) {
    Scene scene;
    scene.setCurves(strands("/a", 10, 2, 0.5f));
    Renderer renderer(gl::GlBackend::Egl);
    Diagnostics diagnostics;
    RenderStats first = renderer.render(scene, squareCamera(64), RenderSettings{}, diagnostics).stats;
    EXPECT_EQ(bytesOf(first, "strandGeometry"), kStrandBytesPerSegment * 20 + kControlPointBytes * 50 + kDrawnPrimBytes);
    // 22 segments: grows to max(22, 20 * 1.5) = 30; 55 controls: to max(55, 50 * 1.5) = 75; 2 prims.
    scene.setCurves(strands("/b", 1, 2, 0.5f));
    RenderStats grown = renderer.render(scene, squareCamera(32), RenderSettings{}, diagnostics).stats;
    EXPECT_EQ(grown.segments, 22u);
    EXPECT_EQ(bytesOf(grown, "strandGeometry"),
              kStrandBytesPerSegment * 30 + kControlPointBytes * 75 + kDrawnPrimBytes * 2);
    EXPECT_EQ(bytesOf(grown, "frameTarget"), 32u * 32u * (16 + 4 + 4));  // the 64 x 64 one is gone
}
