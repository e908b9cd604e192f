// Hair self-shadowing: deep opacity maps and their reference
// (hdHair/plan/DeepOpacityLayers.h, ShadowMapCache.h, ShadowLightView.h),
// rendered. Transmittance is measured as the ratio of a pixel's colour with
// shadows to its colour without: shadows scale each light's irradiance and
// nothing else, so the ratio is T wherever one light shades.

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "DistantLight.h"
#include "OrthographicView.h"
#include "StageRendering.h"
#include "hdHair/image/ImageComparison.h"
#include "hdHair/plan/CameraView.h"
#include "hdHair/render/Renderer.h"
#include "hdHair/scene/Scene.h"
#include "hdHair/scene/tests/AuthoredPrimvar.h"

using namespace hdhair;
using hdhair::test::authoredPrimvar;
using namespace hdhair::testenv;

namespace {

Primvar constant(const std::string& name, std::vector<float> values) {
    const int tupleSize = int(values.size());
    return authoredPrimvar(name, Interpolation::Constant, tupleSize, std::move(values));
}

// Straight white strands along X from x = `from` to `to` (one span each), at
// (y, z) each.
CurvesPrim strandsAlongX(const std::string& path, const std::vector<glm::vec2>& yz, float width, float opacity,
                         float from = -0.95f, float to = 0.95f) {
    CurvesPrim prim;
    prim.path = path;
    prim.type = CurveType::Linear;
    for (const glm::vec2& p : yz) {
        prim.curveVertexCounts.push_back(2);
        prim.points.push_back({from, p.x, p.y});
        prim.points.push_back({to, p.x, p.y});
    }
    prim.primvars["widths"] = constant("widths", {width});
    prim.primvars["displayColor"] = constant("displayColor", {1.0f, 1.0f, 1.0f});
    prim.primvars["displayOpacity"] = constant("displayOpacity", {opacity});
    return prim;
}

// A slab of hair of known density, lit from +Y: `strands` strands along X,
// their (y, z) spread over [-1, 1]^2 by Roberts' R2 sequence (a
// low-discrepancy sequence: every column of light texels, and every row of
// the camera's pixels, meets close to its share of strands, without the
// Poisson spread and the Jensen bias a random slab would add). Each strand
// is kSlabWidth wide with opacity `opacity`: a ray at depth d below the top
// (y = 1) has met, per unit area of the y-z plane, strands / 4 * d strands,
// each covering kSlabWidth around it with alpha `opacity`, so its opacity is
// sigma d, sigma = strands / 4 * width * opacity (sub-texel strands, drawn a
// texel wide with alpha scaled down, sum to the same).
constexpr float kSlabWidth = 0.004f;
constexpr float kAboveSlab = 1.15f;  // one strand above the slab: in front of all hair

double slabSigma(int strands, float opacity) { return strands / 4.0 * kSlabWidth * opacity; }

// `turnDegrees`: the slab turned about the light's axis (Y), so that its
// strands cross the light view's texel rows at that angle (turnedCamera
// sees it as before).
Scene slabScene(int strands = 1000, float opacity = 0.5f, double turnDegrees = 0.0) {
    // R2: the n-th point is frac(0.5 + n / g, 0.5 + n / g^2), g the plastic number.
    const double g = 1.32471795724474602596;
    std::vector<glm::vec2> yz;
    for (int n = 0; n < strands; ++n)
        yz.push_back({float(1.0 - 2.0 * std::fmod(0.5 + n / g, 1.0)),
                      float(-1.0 + 2.0 * std::fmod(0.5 + n / (g * g), 1.0))});
    const glm::mat3 turn(glm::rotate(glm::dmat4(1.0), glm::radians(turnDegrees), glm::dvec3(0.0, 1.0, 0.0)));
    Scene scene;
    for (CurvesPrim prim : {strandsAlongX("/slab", yz, kSlabWidth, opacity),
                            strandsAlongX("/above", {{kAboveSlab, 0.0f}}, kSlabWidth, opacity)}) {
        for (glm::vec3& point : prim.points) point = turn * point;
        scene.setCurves(prim);
    }
    scene.setLight(distantLightFrom({0.0, 1.0, 0.0}));
    return scene;
}

// `camera` turned with the slab about Y: it sees slabScene(..., turnDegrees)
// exactly as `camera` sees the slab unturned.
CameraView turnedCamera(CameraView camera, double turnDegrees) {
    camera.view = camera.view * glm::rotate(glm::dmat4(1.0), glm::radians(-turnDegrees), glm::dvec3(0.0, 1.0, 0.0));
    return camera;
}

RenderResult render(const Scene& scene, const CameraView& camera, const std::vector<std::string>& assignments,
                    Diagnostics* diagnostics = nullptr) {
    RenderSettings settings;
    for (const std::string& assignment : assignments) settings.setFromAssignment(assignment);
    Diagnostics own;
    return sharedRenderer().render(scene, camera, settings, diagnostics ? *diagnostics : own);
}

// Per image row, the summed colour of columns [16, width - 16).
std::vector<double> rowSums(const Image& image) {
    std::vector<double> sums(size_t(image.height), 0.0);
    for (int y = 0; y < image.height; ++y)
        for (int x = 16; x < image.width - 16; ++x)
            for (int c = 0; c < 3; ++c) sums[size_t(y)] += image.at(x, y, c);
    return sums;
}

// The world height of a pixel row's centre in orthographicView(2.4, pixels).
double rowHeight(int row, int pixels) { return 1.2 - (row + 0.5) * 2.4 / pixels; }

bool allFinite(const Image& image) {
    return std::all_of(image.pixels.begin(), image.pixels.end(), [](float v) { return std::isfinite(v); });
}

std::vector<std::string> passNames(const RenderResult& result) {
    std::vector<std::string> names;
    for (const PassTiming& pass : result.stats.passes) names.push_back(pass.name);
    return names;
}

bool ranAShadowPass(const RenderResult& result) {
    for (const std::string& name : passNames(result))
        if (name.rfind("shadow", 0) == 0 || name.rfind("deepOpacity", 0) == 0) return true;
    return false;
}

}  // namespace

// One image row of a slab frame (slabScene, seen by orthographicView(2.4, 64)):
// the transmittance T its strands get (the shadowed row's sum over the
// unshadowed one's) and, inside the slab, -ln T against k sigma d at its
// depth below the slab's top.
struct SlabRow {
    int row = 0;
    double depth = -1.0;  // below the top face; -1 for the strand above the slab
    double transmittance = 1.0;
    double measured = 0.0, expected = 0.0;  // -ln T, and k sigma d
    bool withinTolerance() const { return std::abs(measured - expected) <= 0.02 + 0.04 * expected; }
};

// The rows of the strand above the slab and of the slab within its faces,
// top down. k as DeepOpacityLayers.h states it (kShadowExtinction), written
// out: the expectation must not follow the code it checks.
std::vector<SlabRow> slabRows(const RenderResult& on, const RenderResult& off, double sigma) {
    const double k = 1.0;
    const std::vector<double> shadowed = rowSums(on.color), lit = rowSums(off.color);
    std::vector<SlabRow> rows;
    for (int row = 0; row < 64; ++row) {
        const double y = rowHeight(row, 64);
        if (lit[size_t(row)] <= 0.0) continue;
        SlabRow measured;
        measured.row = row;
        measured.transmittance = shadowed[size_t(row)] / lit[size_t(row)];
        if (std::abs(y - kAboveSlab) >= 0.01) {
            if (y > 0.95 || y < -0.95) continue;  // the slab's faces
            measured.depth = 1.0 - y;
            measured.expected = k * sigma * measured.depth;
            measured.measured = -std::log(measured.transmittance);
        }
        rows.push_back(measured);
    }
    return rows;
}

struct SlabCase {
    const char* name;
    const char* shadowMode;
    const char* strandLines;  // shadowStrandLines
    double turnDegrees;       // the slab turned about the light's axis
    bool drawnAsLines;        // what the light view must draw
};

void PrintTo(const SlabCase& slab, std::ostream* out) { *out << slab.name; }

class SlabTransmittance : public ::testing::TestWithParam<SlabCase> {};

// T = exp(-k opacity) with k = kShadowExtinction = 1, through a slab whose
// opacity grows linearly with depth: -ln T must follow k sigma d row by row,
// fall monotonically with depth, and be 0 (T = 1) above the slab. Deep
// opacity maps with 15 layers: with 3, linear interpolation across the last
// layer (which reaches the bounds, past the slab's last strand) adds up to
// 8 % here, which MoreLayersMoveTowardTheReference measures instead.
//
// The slab's strands are a twentieth of a texel wide, so the maps draw them
// as one-texel lines (shadowStrandLines=auto) or, turned off, as ribbons a
// texel wide. Turned 45 degrees about the light's axis, a line lights one
// texel per diagonal step, 1/sqrt(2) of a ribbon's texels: only the alpha
// it carries for that (strand.tese) keeps -ln T on k sigma d there (without
// it, measured: -ln T up to 0.45 off at 45 degrees and 0.23 at 30, against
// a tolerance of 0.02 + 4 %).
TEST_P(SlabTransmittance, FollowsExpOfMinusKTimesOpacity) {
    const SlabCase& slab = GetParam();
    // Many faint strands: 0.026 alpha per texel, 29 strands a unit of depth
    // in each texel column.
    const int strands = 7500;
    const float opacity = 0.1f;
    const double sigma = slabSigma(strands, opacity);  // 0.75 per unit depth
    const Scene scene = slabScene(strands, opacity, slab.turnDegrees);
    const CameraView camera = turnedCamera(orthographicView(2.4, 64), slab.turnDegrees);
    const std::vector<std::string> settings = {std::string("shadowMode=") + slab.shadowMode, "shadowLayers=15",
                                               "shadowMapResolution=128",
                                               std::string("shadowStrandLines=") + slab.strandLines};
    const RenderResult on = render(scene, camera, settings);
    const RenderResult off = render(scene, camera, {"shadowMode=off"});
    ASSERT_EQ(on.stats.shadowMapsRebuilt, 1u);
    EXPECT_EQ(on.stats.plan.dump().find("one-texel lines") != std::string::npos, slab.drawnAsLines);
    // The slab's strands are straight: drawn, every span skips the
    // tessellator (strandChord.vert draws them), tessellated none; auto (with
    // strandRaster=auto) and compute rasterise them all in compute.
    const std::string strandLines = slab.strandLines;
    const bool straight = slab.drawnAsLines && strandLines == "drawn";
    const bool computed = slab.drawnAsLines && (strandLines == "auto" || strandLines == "compute");
    EXPECT_EQ(on.stats.lightViewStraightSpans > 0, straight);
    EXPECT_EQ(on.stats.lightViewTessellatedSpans, 0u);
    EXPECT_EQ(on.stats.lightViewComputeSpans > 0, computed);
    int checked = 0;
    double worst = 0.0;
    const std::vector<SlabRow> rows = slabRows(on, off, sigma);
    for (size_t i = 0; i < rows.size(); ++i) {
        const SlabRow& row = rows[i];
        if (row.depth < 0.0) {
            // In front of the first strand: nothing shadows it.
            EXPECT_NEAR(row.transmittance, 1.0, 1e-4) << "above the slab";
            continue;
        }
        // Measured: at most 0.046 (deepOpacity) and 0.031 (reference) below
        // k sigma d: the lookup's bias of one texel (sigma x 0.016 = 0.012)
        // and about 2 % from averaging exp(-sum) over texel columns that
        // met a strand more or fewer.
        EXPECT_TRUE(row.withinTolerance()) << "row " << row.row << ", depth " << row.depth << ": -ln T "
                                           << row.measured << ", k sigma d " << row.expected;
        worst = std::max(worst, std::abs(row.measured - row.expected));
        if (row.row % 8 == 0)
            std::printf("%s, depth %.3f: -ln T %.4f, k sigma d %.4f\n", slab.name, row.depth, row.measured,
                        row.expected);
        // Two rows (0.075 deeper, 0.056 more opacity) always darker.
        if (i >= 2 && rows[i - 2].row == row.row - 2 && rows[i - 2].depth >= 0.0) {
            EXPECT_LT(row.transmittance, rows[i - 2].transmittance) << "row " << row.row;
        }
        ++checked;
    }
    std::printf("%s: largest |-ln T - k sigma d| %.4f over %d rows\n", slab.name, worst, checked);
    EXPECT_GT(checked, 45);
}

INSTANTIATE_TEST_SUITE_P(Shadows, SlabTransmittance,
                         ::testing::Values(SlabCase{"deepOpacityLines", "deepOpacity", "auto", 0.0, true},
                                           SlabCase{"deepOpacityLinesTurned45", "deepOpacity", "auto", 45.0, true},
                                           SlabCase{"deepOpacityLinesTurned30", "deepOpacity", "auto", 30.0, true},
                                           SlabCase{"deepOpacityDrawnLines", "deepOpacity", "drawn", 0.0, true},
                                           SlabCase{"deepOpacityDrawnLinesTurned45", "deepOpacity", "drawn", 45.0,
                                                    true},
                                           SlabCase{"deepOpacityComputeLinesTurned30", "deepOpacity", "compute",
                                                    30.0, true},
                                           SlabCase{"deepOpacityTessellatedLinesTurned30", "deepOpacity",
                                                    "tessellated", 30.0, true},
                                           SlabCase{"deepOpacityRibbonsTurned45", "deepOpacity", "off", 45.0, false},
                                           SlabCase{"reference", "reference", "auto", 0.0, false}),
                         [](const ::testing::TestParamInfo<SlabCase>& slabCase) { return std::string(slabCase.param.name); });

// What the slab's check catches in the compute rasteriser's maps
// (shadowStrandLines=compute): maps that sum half the coverage (the slab at
// half the opacity, checked against the full opacity's sigma), and layers
// taken in reverse depth order (the slab lit from below, checked as lit from
// above). Either must put most rows out of tolerance.
TEST(Shadows, ComputeLinesSlabCheckCatchesMutations) {
    const int strands = 7500;
    const double sigma = slabSigma(strands, 0.1f);
    const CameraView camera = orthographicView(2.4, 64);
    const std::vector<std::string> settings = {"shadowLayers=15", "shadowMapResolution=128",
                                               "shadowStrandLines=compute"};
    auto rowsOut = [&](const Scene& scene) {
        const std::vector<SlabRow> rows =
            slabRows(render(scene, camera, settings), render(scene, camera, {"shadowMode=off"}), sigma);
        size_t out = 0, inside = 0;
        for (const SlabRow& row : rows) {
            if (row.depth < 0.0) continue;
            inside += 1;
            out += row.withinTolerance() ? 0 : 1;
        }
        std::printf("%zu of %zu rows out of tolerance\n", out, inside);
        return std::pair{out, inside};
    };
    EXPECT_EQ(rowsOut(slabScene(strands, 0.1f)).first, 0u) << "the unmutated slab";
    const auto [halvedOut, halvedRows] = rowsOut(slabScene(strands, 0.05f));
    EXPECT_GT(halvedOut, halvedRows / 2) << "half the coverage";
    Scene fromBelow = slabScene(strands, 0.1f);
    fromBelow.setLight(distantLightFrom({0.0, -1.0, 0.0}));
    const auto [reversedOut, reversedRows] = rowsOut(fromBelow);
    EXPECT_GT(reversedOut, reversedRows / 2) << "layers in reverse depth order";
}

// A map the compute rasteriser builds again is the same to the bit: its
// opacity sums are integers, whose order does not matter. With float sums
// (atomic compare-and-swap), frames differed in their last bits from one
// build to the next, which a Hydra host rendering again after a cancelled
// frame showed. Renderers of their own build the dense clump's maps; the
// camera's strands are drawn by the hardware, whose blending order is
// fixed (the compute rasteriser's overlong lists are not: transparency.md).
TEST(Shadows, ComputeLinesRebuildTheSameMaps) {
    StageRenderRequest request{"examples/dense_clump.usda", "/World/main_cam", 160, 0.0,
                               {"shadowStrandLines=compute", "strandRaster=hardware", "shadowMapResolution=256",
                                "shadowLayers=7"}};
    Diagnostics diagnostics;
    const Scene scene = readStage(request, diagnostics);
    std::vector<RenderResult> results;
    // Five builds: with float sums one build in two differed here.
    for (int build = 0; build < 5; ++build) {
        Renderer renderer(gl::defaultGlBackend());
        const CameraView camera = stageCamera(scene, request, renderer, diagnostics);
        results.push_back(renderer.render(scene, camera, stageSettings(request), diagnostics));
        ASSERT_GE(results.back().stats.shadowMapsRebuilt, 1u);
        EXPECT_GT(results.back().stats.lightViewComputeSpans, 0u);
    }
    for (size_t build = 1; build < results.size(); ++build)
        EXPECT_EQ(results[build].color.pixels, results[0].color.pixels) << "build " << build;
}

// Hard cases for the light views' compute rasteriser: many strands through
// the same texels (every one of their texels' layer sums contended by all
// of them at once), zero-width strands, and a strand whose segments end
// exactly on texel edges.
TEST(Shadows, ComputeLinesHardCases) {
    const CameraView camera = orthographicView(2.4, 48);
    const std::vector<std::string> computeLines = {"shadowStrandLines=compute", "shadowMapResolution=64",
                                                   "transparency=binSorted"};
    {
        // 20,000 strands in 100 stacks of coincident strands, side by side
        // across 0.6 in z (a few texels), above one receiver, lit from
        // above: the receiver gets no light through them, the stacks' top is
        // lit, and everything is finite.
        Scene scene;
        std::vector<glm::vec2> stacks;
        for (int i = 0; i < 20000; ++i) stacks.push_back({0.5f, -0.3f + 0.6f * float(i % 100) / 99.0f});
        scene.setCurves(strandsAlongX("/stack", stacks, 0.01f, 0.5f));
        scene.setCurves(strandsAlongX("/receiver", {{-0.5f, 0.0f}}, 0.01f, 1.0f));
        scene.setLight(distantLightFrom({0.0, 1.0, 0.0}));
        const RenderResult on = render(scene, camera, computeLines);
        const RenderResult off = render(scene, camera, {"shadowMode=off", "transparency=binSorted"});
        ASSERT_TRUE(allFinite(on.color));
        EXPECT_GE(on.stats.lightViewComputeSpans, on.stats.segments);
        const std::vector<double> shadowed = rowSums(on.color), lit = rowSums(off.color);
        double stackLit = 0.0, stackShadowed = 0.0, receiverLit = 0.0, receiverShadowed = 0.0;
        for (int row = 0; row < 48; ++row) {
            const double y = rowHeight(row, 48);
            if (std::abs(y - 0.5) < 0.05) {
                stackLit += lit[size_t(row)];
                stackShadowed += shadowed[size_t(row)];
            }
            if (std::abs(y + 0.5) < 0.05) {
                receiverLit += lit[size_t(row)];
                receiverShadowed += shadowed[size_t(row)];
            }
        }
        ASSERT_GT(stackLit, 0.0);
        ASSERT_GT(receiverLit, 0.0);
        EXPECT_NEAR(stackShadowed / stackLit, 1.0, 1e-3) << "nothing is in front of the stack";
        EXPECT_LT(receiverShadowed / receiverLit, 1e-3) << "200 strands' opacity in front of every texel";
    }
    {
        // Zero-width strands cover nothing and cast nothing.
        Scene scene = slabScene(2000, 0.5f);
        for (const char* path : {"/slab", "/above"}) {
            CurvesPrim prim = *scene.curves().at(path).prim;
            prim.primvars["widths"] = constant("widths", {0.0f});
            scene.setCurves(prim);
        }
        scene.setCurves(strandsAlongX("/receiver", {{-1.1f, 0.0f}}, 0.01f, 1.0f));
        const RenderResult on = render(scene, camera, computeLines);
        const RenderResult off = render(scene, camera, {"shadowMode=off", "transparency=binSorted"});
        const ImageComparison comparison = compareImages(on.color, off.color, exactWithin(1e-6));
        EXPECT_TRUE(comparison.passed) << "zero-width casters: " << comparison.description;
        EXPECT_GT(comparison.coveredPixels, 0u) << "the receiver is seen";
    }
    {
        // A strand along X in two spans whose shared end lies on a texel
        // edge of the light's view (x = 0, the middle of the fitted bounds):
        // the receiver below it gets the same shadow as under the strand in
        // one span, the texel at the edge counted once.
        CurvesPrim twoSpans = strandsAlongX("/strand", {{0.5f, 0.0f}}, 0.02f, 0.9f);
        twoSpans.curveVertexCounts = {3};
        twoSpans.points = {{-0.95f, 0.5f, 0.0f}, {0.0f, 0.5f, 0.0f}, {0.95f, 0.5f, 0.0f}};
        auto receiverTransmittance = [&](const CurvesPrim& strand) {
            Scene scene;
            scene.setCurves(strand);
            scene.setCurves(strandsAlongX("/receiver", {{-0.5f, 0.0f}}, 0.02f, 1.0f));
            scene.setLight(distantLightFrom({0.0, 1.0, 0.0}));
            const RenderResult on = render(scene, camera, computeLines);
            const std::vector<double> shadowed = rowSums(on.color),
                                      lit = rowSums(render(scene, camera, {"shadowMode=off"}).color);
            double litSum = 0.0, shadowedSum = 0.0;
            for (int row = 0; row < 48; ++row)
                if (std::abs(rowHeight(row, 48) + 0.5) < 0.05) {
                    litSum += lit[size_t(row)];
                    shadowedSum += shadowed[size_t(row)];
                }
            EXPECT_TRUE(allFinite(on.color));
            EXPECT_GT(litSum, 0.0);
            return shadowedSum / litSum;
        };
        const double joined = receiverTransmittance(twoSpans);
        const double single = receiverTransmittance(strandsAlongX("/strand", {{0.5f, 0.0f}}, 0.02f, 0.9f));
        std::printf("receiver's transmittance: two spans %.5f, one span %.5f\n", joined, single);
        EXPECT_LT(single, 0.9) << "the strand shadows the receiver";
        EXPECT_NEAR(joined, single, 5e-4);
    }
}

TEST(Shadows, MoreLayersMoveTowardTheReference) {
    StageRenderRequest request{"examples/dense_clump.usda", "/World/main_cam", 96, 0.0,
                               {"shadowMode=reference", "shadowMapResolution=256"}};
    const Image reference = renderStage(request).result.color;
    std::vector<double> errors;
    for (const char* layers : {"3", "15"}) {
        request.settings = {"shadowMapResolution=256", std::string("shadowLayers=") + layers};
        errors.push_back(compareImages(renderStage(request).result.color, reference, exactWithin(1.0 / 255.0))
                             .rootMeanSquare);
    }
    std::printf("RMSE against the reference: 3 layers %.5f, 15 layers %.5f\n", errors[0], errors[1]);
    EXPECT_LT(errors[1], 0.7 * errors[0]) << "15 layers must be clearly closer to the reference than 3";
}

TEST(Shadows, MapsAreKeptHoweverTheCameraMovesAndRebuiltWhenALightDoes) {
    Diagnostics diagnostics;
    Scene scene;
    StageRenderRequest request{"examples/straight_strands.usda", "/World/main_cam", 96, 0.0, {}};
    scene = readStage(request, diagnostics);
    CameraView camera = stageCamera(scene, request, sharedRenderer(), diagnostics);
    // The hardware rasteriser, whose bin sort runs every frame, beside the passes kept.
    const std::vector<std::string> settings = {"shadowMapResolution=128", "strandRaster=hardware"};
    RenderResult first = render(scene, camera, settings);
    EXPECT_EQ(first.stats.shadowMapsRebuilt, 2u);
    EXPECT_TRUE(ranAShadowPass(first));

    // The camera orbits 35 degrees about the hair: both maps kept, no shadow
    // pass runs (the light views tessellate by their own texels, so nothing
    // of a map depends on the camera).
    camera.view = camera.view * glm::rotate(glm::dmat4(1.0), glm::radians(35.0), glm::dvec3(0, 1, 0));
    RenderResult moved = render(scene, camera, settings);
    EXPECT_EQ(moved.stats.shadowMapsRebuilt, 0u);
    EXPECT_EQ(moved.stats.shadowMapsKept, 2u);
    EXPECT_FALSE(ranAShadowPass(moved));
    EXPECT_NE(moved.stats.toJson()["plan"].dump().find("kept: light, hair and settings unchanged"),
              std::string::npos);

    // An intensity edit changes no map; turning a light rebuilds its own.
    std::string key;
    for (const auto& [path, entry] : scene.lights())
        if (entry.prim->type == LightType::Distant) key = path;
    ASSERT_FALSE(key.empty());
    LightPrim light = *scene.lights().at(key).prim;
    light.intensity *= 2.0f;
    scene.setLight(light);
    EXPECT_EQ(render(scene, camera, settings).stats.shadowMapsRebuilt, 0u);
    light.worldTransform = glm::rotate(glm::dmat4(1.0), 0.2, glm::dvec3(0, 1, 0)) * light.worldTransform;
    scene.setLight(light);
    RenderResult turned = render(scene, camera, settings);
    EXPECT_EQ(turned.stats.shadowMapsRebuilt, 1u);
    EXPECT_EQ(turned.stats.shadowMapsKept, 1u);
    EXPECT_EQ(passNames(turned), (std::vector<std::string>{"prepareCurves", "upload", "sort", "shadowDepth " + key,
                                                           "deepOpacity " + key, "clear", "strands", "readback"}));

    // The kept maps, built for the first camera, shade exactly as ones a
    // fresh renderer builds for this camera.
    Renderer fresh(gl::GlBackend::Egl);
    RenderSettings renderSettings = RenderSettings::fromAssignments(Complexity::Low, settings);
    ImageComparison comparison = compareImages(render(scene, camera, settings).color,
                                               fresh.render(scene, camera, renderSettings, diagnostics).color,
                                               exactWithin(1e-6));
    EXPECT_TRUE(comparison.passed) << comparison.description;
}

TEST(Shadows, TheCameraLightsMapFollowsTheCamera) {
    Scene scene = slabScene();
    scene.remove("/light");  // no stage light: the camera light shines, and casts when asked
    CameraView camera = orthographicView(2.4, 48);
    const std::vector<std::string> casting{"shadowMapResolution=64", "cameraLightShadows=on"};
    EXPECT_EQ(render(scene, camera, {"shadowMapResolution=64"}).stats.shadowMapsRebuilt, 0u);
    EXPECT_EQ(render(scene, camera, casting).stats.shadowMapsRebuilt, 1u);
    EXPECT_EQ(render(scene, camera, casting).stats.shadowMapsKept, 1u);
    camera.view = glm::rotate(glm::dmat4(1.0), 0.05, glm::dvec3(0, 1, 0)) * camera.view;
    RenderResult moved = render(scene, camera, casting);
    EXPECT_EQ(moved.stats.shadowMapsRebuilt, 1u);
    EXPECT_EQ(moved.stats.shadowMaps[0]["reason"], "rebuilt: the camera moved, and the camera light with it");
}

TEST(Shadows, AStageWithoutShadowCastingLightsBuildsNoShadowPasses) {
    Scene scene = slabScene();
    LightPrim light = *scene.lights().at("/light").prim;
    light.shadowEnable = false;
    scene.setLight(light);
    const CameraView camera = orthographicView(2.4, 32);
    RenderResult result = render(scene, camera, {});
    EXPECT_EQ(result.stats.shadowMapsRebuilt + result.stats.shadowMapsKept, 0u);
    // The plan is kept in a variable: a range-for over a temporary's member
    // would walk freed memory (found by AddressSanitizer).
    const nlohmann::json stats = result.stats.toJson();
    for (const auto& pass : stats["plan"]) {
        const std::string name = pass["pass"];
        EXPECT_TRUE(name.rfind("shadow", 0) != 0 && name.rfind("deepOpacity", 0) != 0) << name;
    }
    // Flat shading reads no light: the maps are planned but not built, and say why.
    light.shadowEnable = true;
    scene.setLight(light);
    RenderResult flat = render(scene, camera, {"shadingModel=flat"});
    EXPECT_FALSE(ranAShadowPass(flat));
    EXPECT_NE(flat.stats.toJson()["plan"].dump().find("every prim is flat-shaded, so no pass reads lights or their "
                                                      "shadows; not built: nothing reads its output"),
              std::string::npos);
}

// Single scattering: multiple scattering (testMultipleScattering) reads the
// transmittance its own way.
TEST(Shadows, KajiyaKayAndMarschnerAreShadowedAlike) {
    const Scene scene = slabScene();
    const CameraView camera = orthographicView(2.4, 64);
    std::vector<double> transmittances;
    for (const char* model : {"kajiyaKay", "marschner"}) {
        const std::string setting = std::string("shadingModel=") + model;
        const std::vector<double> on =
            rowSums(render(scene, camera, {setting, "shadowMapResolution=128", "multipleScattering=off"}).color);
        const std::vector<double> off =
            rowSums(render(scene, camera, {setting, "shadowMode=off", "multipleScattering=off"}).color);
        transmittances.push_back(on[48] / off[48]);  // y = -0.3: deep in the slab
    }
    EXPECT_LT(transmittances[0], 0.6);
    EXPECT_NEAR(transmittances[0], transmittances[1], 1e-3);
}

// Vertex shadows (shadowSampling=vertex, the default) look each light up at
// the tessellated points and interpolate along the segment. A long straight
// strand is one segment by the error rule, so its points are cut no more
// than a texel of the map apart: here half of it lies under a block of hair
// that shadows the light from above, the other half in the open, and it must
// show the same edge per fragment and per point. A second light from below
// reaches all of it: each light keeps its own transmittance.
TEST(Shadows, VertexShadowsFollowAShadowsEdgeAlongALongStraightStrand) {
    Scene scene;
    std::vector<glm::vec2> block;
    // 10 layers in y, each of 41 strands 0.02 wide every 0.01 in z: every
    // texel column over the strand meets hair in every layer.
    for (int i = 0; i < 410; ++i)
        block.push_back({0.3f + 0.7f * float(i % 10) / 9.0f, -0.2f + 0.4f * float(i / 10) / 40.0f});
    scene.setCurves(strandsAlongX("/block", block, 0.02f, 0.6f, -0.95f, 0.0f));
    scene.setCurves(strandsAlongX("/strand", {{-0.5f, 0.0f}}, 0.08f, 1.0f));
    scene.setLight(distantLightFrom({0.0, 1.0, 0.0}, "/above"));
    scene.setLight(distantLightFrom({0.0, -1.0, 0.0}, "/below", 1.0f));
    const CameraView camera = orthographicView(2.4, 64);
    const RenderResult perPoint = render(scene, camera, {"shadowSampling=vertex", "shadowMapResolution=128"});
    const RenderResult perFragment = render(scene, camera, {"shadowSampling=fragment", "shadowMapResolution=128"});
    const RenderResult unshadowed = render(scene, camera, {"shadowMode=off"});
    ASSERT_FALSE(perPoint.stats.strandShaders.empty());
    ASSERT_FALSE(perFragment.stats.strandShaders.empty());
    EXPECT_NE(perPoint.stats.strandShaders.front().find("vertexShadows"), std::string::npos);
    EXPECT_EQ(perFragment.stats.strandShaders.front().find("vertexShadows"), std::string::npos);

    // The strand's rows (y = -0.5, 2 pixels wide): its colour per column
    // over its colour unshadowed.
    auto transmittanceAt = [&](const RenderResult& result, int column) {
        double shadowed = 0.0, lit = 0.0;
        for (int row = 0; row < 64; ++row) {
            if (std::abs(rowHeight(row, 64) + 0.5) > 0.05) continue;
            for (int c = 0; c < 3; ++c) {
                shadowed += result.color.at(column, row, c);
                lit += unshadowed.color.at(column, row, c);
            }
        }
        return lit > 0.0 ? shadowed / lit : -1.0;
    };
    int checked = 0;
    double worst = 0.0;
    for (int column = 4; column < 60; ++column) {
        const double x = -1.2 + (column + 0.5) * 2.4 / 64.0;
        // The edge: the block's end at x = 0, blurred by a texel (0.016) of
        // the bilinear lookup either way, and 3 pixels of margin.
        if (std::abs(x) < 0.12 || std::abs(x) > 0.9) continue;
        const double fragment = transmittanceAt(perFragment, column), vertex = transmittanceAt(perPoint, column);
        ASSERT_GE(fragment, 0.0) << "column " << column << " misses the strand";
        if (x < -0.2) {
            EXPECT_LT(fragment, 0.75) << "x " << x << ": the block shadows the light from above";
        } else if (x > 0.2) {
            EXPECT_NEAR(fragment, 1.0, 1e-3) << "x " << x << ": both lights reach the strand";
        }
        EXPECT_NEAR(vertex, fragment, 0.01) << "x " << x;
        worst = std::max(worst, std::abs(vertex - fragment));
        ++checked;
    }
    std::printf("largest |T per point - T per fragment| along the strand: %.4f over %d columns\n", worst, checked);
    EXPECT_GT(checked, 30);
}

// Each view cuts the spans by its own error rule, the camera in pixels and a
// light view in its map's texels. A span that bends along the light looks
// straight from it, yet the camera's points lie on the bend: a light view
// that drew the chord would have the strand shadow itself by the sagitta
// (here 9 texels, far past the one-texel bias). The rule bounds the
// polyline's distance from the curve in depth too (strand.tesc), so a lone
// strand is lit all along, per fragment and per point.
TEST(Shadows, AStrandBentAlongTheLightDoesNotShadowItself) {
    CurvesPrim arc;
    arc.path = "/arc";
    arc.type = CurveType::Cubic;
    arc.basis = CurveBasis::Bezier;
    arc.curveVertexCounts = {4};
    // One Bezier span, uniformly spaced in x and bulging 0.03 away from the
    // light (-y): from above it is the straight segment [-0.8, 0.8].
    arc.points = {{-0.8f, 0.0f, 0.0f}, {-0.8f / 3.0f, -0.04f, 0.0f}, {0.8f / 3.0f, -0.04f, 0.0f}, {0.8f, 0.0f, 0.0f}};
    arc.primvars["widths"] = constant("widths", {0.05f});
    arc.primvars["displayColor"] = constant("displayColor", {1.0f, 1.0f, 1.0f});
    arc.primvars["displayOpacity"] = constant("displayOpacity", {1.0f});
    Scene scene;
    scene.setCurves(arc);
    scene.setLight(distantLightFrom({0.0, 1.0, 0.0}));
    const CameraView camera = orthographicView(2.4, 128);
    const RenderResult unshadowed = render(scene, camera, {"shadowMode=off"});
    for (const char* sampling : {"fragment", "vertex"}) {
        const RenderResult shadowed = render(scene, camera, {std::string("shadowSampling=") + sampling});
        EXPECT_EQ(shadowed.stats.shadowMapsRebuilt, 1u);
        int covered = 0;
        double darkest = 1.0;
        for (int y = 0; y < 128; ++y)
            for (int x = 0; x < 128; ++x) {
                // Pixels both frames cover: vertex shadows cut the camera's
                // span finer, which moves the ribbon's edges by a fraction
                // of a pixel.
                if (unshadowed.color.at(x, y, 3) < 0.5 || shadowed.color.at(x, y, 3) < 0.5) continue;
                ++covered;
                const double lit = unshadowed.color.at(x, y, 0);
                if (lit > 0.0) darkest = std::min(darkest, shadowed.color.at(x, y, 0) / lit);
            }
        std::printf("shadowSampling=%s: darkest pixel of the arc %.4f of its unshadowed colour (%d pixels)\n", sampling,
                    darkest, covered);
        EXPECT_GT(covered, 100);
        EXPECT_GT(darkest, 0.99) << sampling << ": the strand shadows itself";
    }
}

// shadowSampling=auto takes vertex shadows where cutting every span to 2
// texels of the map would average at most 4 segments a span, as on real
// grooms, and looks up per fragment where the spans are long: the slab's
// strands are one span each across the whole map; the same strands as 200
// spans each are short. The frame says which, and why.
TEST(Shadows, AutoSamplingTakesVertexShadowsOnlyWhereTheSpansAreShort) {
    const CameraView camera = orthographicView(2.4, 48);
    auto sampledPerPoint = [&](const Scene& scene) {
        const RenderResult result = render(scene, camera, {"shadowMapResolution=128"});
        EXPECT_NE(result.stats.plan.dump().find("shadowSampling=auto"), std::string::npos);
        return !result.stats.strandShaders.empty() &&
               result.stats.strandShaders.front().find("vertexShadows") != std::string::npos;
    };
    EXPECT_FALSE(sampledPerPoint(slabScene(200))) << "one span across the map";
    Scene shortSpans = slabScene(200);
    CurvesPrim slab = *shortSpans.curves().at("/slab").prim;
    CurvesPrim split = slab;
    split.curveVertexCounts.assign(slab.curveVertexCounts.size(), 201);
    split.points.clear();
    for (size_t curve = 0; curve < slab.curveVertexCounts.size(); ++curve) {
        const glm::vec3 from = slab.points[2 * curve], to = slab.points[2 * curve + 1];
        for (int k = 0; k <= 200; ++k) split.points.push_back(from + (to - from) * (float(k) / 200.0f));
    }
    shortSpans.setCurves(split);
    EXPECT_TRUE(sampledPerPoint(shortSpans)) << "200 spans a strand";
}

// Lines stand in for ribbons only where a ribbon would be drawn a texel wide
// with its alpha scaled down: every strand at most a texel wide in the
// light's view, and minPixelWidth at most 1.
TEST(Shadows, LightViewsDrawLinesOnlyWhereNoStrandIsWiderThanATexel) {
    const CameraView camera = orthographicView(2.4, 32);
    auto lightViewDraws = [&](const Scene& scene, std::vector<std::string> settings) {
        settings.push_back("shadowMapResolution=128");  // texels of about 0.02 here
        const std::string plan = render(scene, camera, settings).stats.plan.dump();
        if (plan.find("strands as one-texel lines") != std::string::npos) return std::string("lines");
        const size_t ribbons = plan.find("strands as ribbons (");
        return ribbons == std::string::npos ? std::string("neither") : plan.substr(ribbons + 20, 12);
    };
    EXPECT_EQ(lightViewDraws(slabScene(200), {}), "lines") << "0.004 wide";
    Scene wide = slabScene(200);
    wide.setCurves(strandsAlongX("/wide", {{0.0f, 0.0f}}, 0.05f, 1.0f));
    EXPECT_EQ(lightViewDraws(wide, {}), "the widest i") << "one strand of 0.05";
    EXPECT_EQ(lightViewDraws(slabScene(200), {"minPixelWidth=2"}), "minPixelWidt");
    EXPECT_EQ(lightViewDraws(slabScene(200), {"shadowStrandLines=tessellated"}), "lines");
    EXPECT_EQ(lightViewDraws(slabScene(200), {"shadowStrandLines=drawn"}), "lines");
    EXPECT_EQ(lightViewDraws(slabScene(200), {"shadowStrandLines=compute"}), "lines");
    EXPECT_EQ(lightViewDraws(slabScene(200), {"shadowStrandLines=off"}), "shadowStrand");
    EXPECT_EQ(lightViewDraws(slabScene(200), {"shadowMode=reference"}), "neither") << "the reference draws ribbons";
}

// shadowStrandLines=drawn draws the spans a light view leaves one segment as
// plain lines (gl/LightViewSpans.h, strandChord.vert), without the
// tessellator; `tessellated` sends every span through it. The ends of a
// one-segment isoline are the span's ends, so the maps, and the frame that
// reads them, must be the same up to the order the opacity layers sum in
// (half-float sums). On the wavy stage's map at 96 texels (its strands
// 0.81 texels wide there, so lines) the waves and curls keep most spans on
// the tessellator and some off it. The check's reach: the same frame with
// every span drawn as its chord (a tolerance of 100 texels leaves nearly all
// one segment) must fail it.
TEST(Shadows, StraightSpansSkipTheTessellatorWithTheSameMaps) {
    StageRenderRequest request{"examples/wavy_strands.usda", "/World/main_cam", 160, 0.0, {}};
    auto renderWith = [&](std::vector<std::string> settings) {
        settings.push_back("shadowMapResolution=96");
        request.settings = std::move(settings);
        return renderStage(request).result;
    };
    const RenderResult tessellated = renderWith({"shadowStrandLines=tessellated"});
    const RenderResult straight = renderWith({"shadowStrandLines=drawn"});
    const RenderResult chords = renderWith({"shadowStrandLines=drawn", "shadowTessellationTolerance=100"});
    ASSERT_NE(straight.stats.plan.dump().find("spans of one segment without the tessellator"), std::string::npos);
    ASSERT_NE(tessellated.stats.plan.dump().find("every span through the tessellator"), std::string::npos);
    EXPECT_EQ(tessellated.stats.lightViewStraightSpans + tessellated.stats.lightViewTessellatedSpans, 0u);
    EXPECT_GT(straight.stats.lightViewStraightSpans, 0u);
    EXPECT_GT(straight.stats.lightViewTessellatedSpans, 0u) << "the curls bend within a texel's tolerance";
    EXPECT_LE(straight.stats.lightViewStraightSpans + straight.stats.lightViewTessellatedSpans,
              straight.stats.segments);
    EXPECT_GT(chords.stats.lightViewStraightSpans, straight.stats.lightViewStraightSpans);

    const CoveredPixelTolerance sameMaps = exactWithin(2e-3);
    const ImageComparison same = compareImages(straight.color, tessellated.color, sameMaps);
    EXPECT_TRUE(same.passed) << same.description;
    EXPECT_GT(same.coveredPixels, 1000u);
    const ImageComparison mutated = compareImages(chords.color, tessellated.color, sameMaps);
    EXPECT_FALSE(mutated.passed) << "chords for curved spans must show: " << mutated.description;
    std::printf("straight spans %llu, tessellated %llu; largest difference %.5f, with chords everywhere %.5f\n",
                static_cast<unsigned long long>(straight.stats.lightViewStraightSpans),
                static_cast<unsigned long long>(straight.stats.lightViewTessellatedSpans), same.maxDifference,
                mutated.maxDifference);
}

// The light views' compute rasteriser (shadowStrandLines=compute,
// gl/LightViewRaster.h) against the draws (drawn), with the camera's strands
// drawn by the hardware in both, so that only the maps differ. Its lines
// light texels by the Bresenham rule rather than llvmpipe's, so texels
// differ where a line passes near a texel's edge, and strands in the frame
// move between nearby shadow values: the frames agree within
// sameMaps (what the slab's check, ComputeLinesSlabCheckCatchesMutations,
// holds to the analytic truth), and against shadowMode=reference (every fragment of the
// view kept) the compute maps come no further than the drawn ones.
TEST(Shadows, ComputeLinesMatchTheDrawnMapsAndTheReference) {
    struct StageCase {
        const char* stage;
        int width;
        const char* resolution;  // shadowMapResolution: lines there (widest under 1.5 texels)
    };
    for (const StageCase& stage : {StageCase{"examples/wavy_strands.usda", 160, "96"},
                                   StageCase{"examples/dense_clump.usda", 128, "256"}}) {
        StageRenderRequest request{stage.stage, "/World/main_cam", stage.width, 0.0, {}};
        auto renderWith = [&](const std::string& setting) {
            request.settings = {"strandRaster=hardware", std::string("shadowMapResolution=") + stage.resolution,
                                setting};
            return renderStage(request).result;
        };
        const RenderResult drawn = renderWith("shadowStrandLines=drawn");
        const RenderResult computed = renderWith("shadowStrandLines=compute");
        const RenderResult reference = renderWith("shadowMode=reference");
        SCOPED_TRACE(stage.stage);
        ASSERT_NE(computed.stats.plan.dump().find("rasterised in compute (shadowStrandLines=compute)"),
                  std::string::npos);
        EXPECT_GE(computed.stats.lightViewComputeSpans, computed.stats.segments);
        EXPECT_EQ(computed.stats.lightViewStraightSpans + computed.stats.lightViewTessellatedSpans, 0u);
        EXPECT_GT(drawn.stats.lightViewStraightSpans, 0u);

        // Measured: 3.9 % of the wavy stage's pixels over 1/255, none over
        // 0.054, RMSE 0.0015; the dense clump's 0.1 % and 0.00025.
        CoveredPixelTolerance sameMaps;
        sameMaps.threshold = 1.0 / 255.0;
        sameMaps.allowedShareOverThreshold = 0.12;
        sameMaps.outlierLimit = 0.1;
        sameMaps.allowedOutliers = 0;
        const ImageComparison between = compareImages(computed.color, drawn.color, sameMaps);
        const double computedError =
            compareImages(computed.color, reference.color, exactWithin(1.0 / 255.0)).rootMeanSquare;
        const double drawnError = compareImages(drawn.color, reference.color, exactWithin(1.0 / 255.0)).rootMeanSquare;
        std::printf("%s: compute against drawn: %s; RMSE against the reference: compute %.5f, drawn %.5f\n",
                    stage.stage, between.description.c_str(), computedError, drawnError);
        EXPECT_TRUE(between.passed) << between.description;
        EXPECT_LT(between.rootMeanSquare, 0.004);
        EXPECT_GT(between.coveredPixels, 1000u);
        EXPECT_LT(computedError, 1.1 * drawnError);
    }
}

TEST(Shadows, LightsBeyondTheFirstBatchKeepTheirMaps) {
    Scene scene = slabScene();
    for (int i = 1; i < 5; ++i)
        scene.setLight(distantLightFrom({0.1 * i, 1.0, 0.05 * i}, "/light" + std::to_string(i), 0.5f));
    const CameraView camera = orthographicView(2.4, 48);
    const RenderResult split = render(scene, camera, {"lightsPerPass=4", "shadowMapResolution=64"});
    EXPECT_EQ(split.stats.shadowMapsRebuilt, 5u);
    EXPECT_EQ(split.stats.lightPasses, 2u);
    const RenderResult together = render(scene, camera, {"lightsPerPass=16", "shadowMapResolution=64"});
    EXPECT_EQ(together.stats.shadowMapsKept, 5u) << "batching does not change a map";
    ImageComparison comparison = compareImages(split.color, together.color, exactWithin(1.0 / 255.0));
    EXPECT_TRUE(comparison.passed) << comparison.description;
}

TEST(Shadows, HardCasesStayFiniteAndSayWhatTheyDid) {
    const CameraView camera = orthographicView(2.4, 48);
    auto renderChecked = [&](const Scene& scene, std::vector<std::string> settings, Diagnostics* diagnostics) {
        settings.push_back("shadowMapResolution=64");
        RenderResult result = render(scene, camera, settings, diagnostics);
        EXPECT_TRUE(allFinite(result.color));
        return result;
    };
    {
        // All hair at one depth from the light: nothing is in front of anything.
        Scene scene;
        std::vector<glm::vec2> yz;
        for (int i = 0; i < 40; ++i) yz.push_back({0.0f, -1.0f + 0.05f * float(i)});
        scene.setCurves(strandsAlongX("/flat", yz, 0.02f, 0.8f));
        scene.setLight(distantLightFrom({0.0, 1.0, 0.0}));
        Diagnostics diagnostics;
        const Image on = renderChecked(scene, {}, &diagnostics).color;
        const Image off = renderChecked(scene, {"shadowMode=off"}, &diagnostics).color;
        ImageComparison comparison = compareImages(on, off, exactWithin(1e-5));
        EXPECT_TRUE(comparison.passed) << "one depth: " << comparison.description;
        EXPECT_EQ(diagnostics.warningCount(), 0u);
    }
    {
        // The light along the strands, and a single strand.
        Scene scene;
        scene.setCurves(strandsAlongX("/one", {{0.0f, 0.0f}}, 0.05f, 0.7f));
        scene.setLight(distantLightFrom({1.0, 0.0, 0.0}));
        Diagnostics diagnostics;
        RenderResult result = renderChecked(scene, {}, &diagnostics);
        EXPECT_EQ(result.stats.shadowMapsRebuilt, 1u);
        EXPECT_GT(coverage(result.color), 0.0);
        EXPECT_EQ(diagnostics.warningCount(), 0u);
    }
    {
        // Zero opacity: nothing drawn, nothing cast.
        Scene scene;
        scene.setCurves(strandsAlongX("/ghost", {{0.0f, 0.0f}, {0.5f, 0.0f}}, 0.05f, 0.0f));
        scene.setLight(distantLightFrom({0.0, 1.0, 0.0}));
        Diagnostics diagnostics;
        const Image image = renderChecked(scene, {}, &diagnostics).color;
        EXPECT_EQ(*std::max_element(image.pixels.begin(), image.pixels.end()), 0.0f);
    }
    for (glm::dvec3 position : {glm::dvec3(0.0, 0.0, 0.0), glm::dvec3(0.95, 0.0, 0.0)}) {
        // A sphere light inside, then touching, the hair's bounds: no map.
        // Under deepOpacity a warning, and the light still shades
        // unshadowed; under auto (the default) the density volume shadows
        // it, without a warning, and the frame is finite and darker.
        Scene scene = slabScene();
        scene.remove("/light");
        LightPrim bulb;
        bulb.path = "/bulb";
        bulb.type = LightType::Sphere;
        bulb.intensity = 0.5f;
        bulb.worldTransform = glm::translate(glm::dmat4(1.0), position);
        scene.setLight(bulb);
        Diagnostics autoDiagnostics;
        const RenderResult volume = renderChecked(scene, {}, &autoDiagnostics);
        EXPECT_EQ(autoDiagnostics.warningCount(), 0u);
        EXPECT_TRUE(volume.plan.isEnabled("densityVolume"));
        for (float value : volume.color.pixels) ASSERT_TRUE(std::isfinite(value));
        Diagnostics diagnostics;
        const RenderResult on = renderChecked(scene, {"shadowMode=deepOpacity"}, &diagnostics);
        EXPECT_LT(std::accumulate(volume.color.pixels.begin(), volume.color.pixels.end(), 0.0),
                  std::accumulate(on.color.pixels.begin(), on.color.pixels.end(), 0.0));
        ASSERT_EQ(diagnostics.warningCount(), 1u);
        EXPECT_EQ(diagnostics.warnings()[0].where, "/bulb");
        EXPECT_NE(diagnostics.warnings()[0].message.find("inside or too close to the hair's bounds"), std::string::npos);
        EXPECT_EQ(on.stats.shadowMapsRebuilt, 0u);
        const RenderResult off = renderChecked(scene, {"shadowMode=off"}, &diagnostics);
        ImageComparison comparison = compareImages(on.color, off.color, exactWithin(1e-6));
        EXPECT_TRUE(comparison.passed) << comparison.description;
    }
}
