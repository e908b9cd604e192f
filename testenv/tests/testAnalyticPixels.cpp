// Pixels computed by hand. Flat shading (displayColor x opacity, no light),
// an orthographic view 4 units across at 128 px (32 px a unit, pixel (0, 0)'s
// corner at world (-2, 2)) and opaque strands 6 px wide placed on pixel
// boundaries: a pixel is covered when its centre lies inside the ribbon, so
// which pixels a strand covers is exact, with half a pixel to spare on every
// side, and every covered pixel holds the colour the primvars give exactly.
// Tessellation is as fine as it goes (64 segments a 32 px span: a vertex at
// every pixel centre), so colours at pixel centres are the curve's own.

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <glm/common.hpp>
#include <gtest/gtest.h>

#include "OrthographicView.h"
#include "StageRendering.h"
#include "hdHair/curves/CatmullRomEvaluation.h"
#include "hdHair/scene/Scene.h"
#include "hdHair/scene/tests/AuthoredPrimvar.h"
#include "hdHair/usda/SceneReader.h"
#include "hdHair/usda/Stage.h"

using namespace hdhair;
using namespace hdhair::testenv;
using hdhair::test::authoredPrimvar;

namespace {

constexpr int kPixels = 128;
constexpr double kPixelsPerUnit = 32.0;
constexpr double kStrandPixels = 6.0;
constexpr float kExact = 1e-3f;

// The world point at pixel coordinates (x right, y down, in pixels).
glm::vec3 at(double x, double y) {
    return glm::vec3(float(x / kPixelsPerUnit - 2.0), float(2.0 - y / kPixelsPerUnit), 0.0f);
}

Primvar displayColors(Interpolation interpolation, const std::vector<glm::vec3>& colors) {
    std::vector<float> values;
    for (const glm::vec3& c : colors) values.insert(values.end(), {c.r, c.g, c.b});
    return authoredPrimvar("displayColor", interpolation, 3, values);
}

CurvesPrim strand(const std::string& path, CurveType type, CurveBasis basis, CurveWrap wrap, std::vector<int> counts,
                  std::vector<glm::vec3> points, glm::vec3 color) {
    CurvesPrim prim;
    prim.path = path;
    prim.type = type;
    prim.basis = basis;
    prim.wrap = wrap;
    prim.curveVertexCounts = std::move(counts);
    prim.points = std::move(points);
    prim.primvars["widths"] =
        authoredPrimvar("widths", Interpolation::Constant, 1, {float(kStrandPixels / kPixelsPerUnit)});
    prim.primvars["displayColor"] = displayColors(Interpolation::Constant, {color});
    return prim;
}

Image renderFlat(const Scene& scene, const char* expectedPath = "opaque") {
    RenderSettings settings;
    settings.set("shadingModel", "flat");
    settings.set("tessellationTolerance", "0.01");
    settings.set("maxSegmentsPerSpan", "64");
    Diagnostics diagnostics;
    RenderResult result =
        sharedRenderer().render(scene, orthographicView(kPixels / kPixelsPerUnit, kPixels), settings, diagnostics);
    EXPECT_TRUE(diagnostics.warnings().empty()) << diagnostics.warnings().front().message;
    EXPECT_EQ(result.stats.transparency, expectedPath) << "opaque strands 6 px wide need no blending; others blend";
    return result.color;
}

Image renderFlat(const CurvesPrim& prim) {
    Scene scene;
    scene.setCurves(prim);
    return renderFlat(scene);
}

// The covered pixels of one row or column, as runs of consecutive indices.
struct CoveredRun {
    int first, last;
    bool operator==(const CoveredRun& other) const { return first == other.first && last == other.last; }
};
using Runs = std::vector<CoveredRun>;
std::ostream& operator<<(std::ostream& out, const CoveredRun& run) {
    return out << "[" << run.first << ", " << run.last << "]";
}

Runs coveredRuns(const Image& image, int fixed, bool alongRow) {
    Runs runs;
    int length = alongRow ? image.width : image.height;
    for (int i = 0; i < length; ++i) {
        bool covered = (alongRow ? image.at(i, fixed, 3) : image.at(fixed, i, 3)) > 0.0f;
        if (!covered) continue;
        if (!runs.empty() && runs.back().last == i - 1)
            runs.back().last = i;
        else
            runs.push_back({i, i});
    }
    return runs;
}
Runs coveredColumns(const Image& image, int row) { return coveredRuns(image, row, true); }
Runs coveredRows(const Image& image, int column) { return coveredRuns(image, column, false); }

// Pre-multiplied: colour times alpha.
void expectPixel(const Image& image, int x, int y, glm::vec3 color, const std::string& what, float alpha = 1.0f) {
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(image.at(x, y, c), color[c] * alpha, kExact) << what << " (" << x << ", " << y << ") channel " << c;
    EXPECT_NEAR(image.at(x, y, 3), alpha, kExact) << what << " (" << x << ", " << y << ") alpha";
}

void expectEmpty(const Image& image, int x, int y, const std::string& what) {
    EXPECT_EQ(image.at(x, y, 3), 0.0f) << what << " (" << x << ", " << y << ") should be empty";
}

}  // namespace

TEST(AnalyticPixels, OpenCurvesOfEveryBasisStartAndEndWhereTheirBasisSays) {
    // Collinear control points on the row boundary y = 64: every basis draws
    // a straight 6 px ribbon over rows 61..66, from and to the points its
    // basis passes through, cut square at its ends.
    struct Case {
        const char* name;
        CurveType type;
        CurveBasis basis;
        CurveWrap wrap;
        std::vector<double> x;        // control points' pixel columns
        int firstColumn, lastColumn;  // covered: pixel centres within [start, end]
    };
    const Case cases[] = {
        // Linear and bezier pass through their first and last points: x 16 to 64.
        {"linear", CurveType::Linear, CurveBasis::Bezier, CurveWrap::Nonperiodic, {16, 40, 64}, 16, 63},
        {"bezier", CurveType::Cubic, CurveBasis::Bezier, CurveWrap::Nonperiodic, {16, 24, 56, 64}, 16, 63},
        // bspline runs from (P0 + 4 P1 + P2) / 6 = 20 to (P2 + 4 P3 + P4) / 6 = 60,
        // catmullRom from P1 to P3: 16 to 64.
        {"bspline", CurveType::Cubic, CurveBasis::Bspline, CurveWrap::Nonperiodic, {16, 16, 40, 64, 64}, 20, 59},
        {"catmullRom", CurveType::Cubic, CurveBasis::CatmullRom, CurveWrap::Nonperiodic, {16, 16, 40, 64, 64}, 16, 63},
        // Pinned curves start and end on their end points: 16 to 64.
        {"pinned bspline", CurveType::Cubic, CurveBasis::Bspline, CurveWrap::Pinned, {16, 40, 64}, 16, 63},
        {"pinned catmullRom", CurveType::Cubic, CurveBasis::CatmullRom, CurveWrap::Pinned, {16, 40, 64}, 16, 63},
    };
    const glm::vec3 color(0.8f, 0.3f, 0.1f);
    for (const Case& c : cases) {
        std::vector<glm::vec3> points;
        for (double x : c.x) points.push_back(at(x, 64.0));
        Image image = renderFlat(strand("/curve", c.type, c.basis, c.wrap, {int(points.size())}, points, color));
        for (int row : {61, 63, 66})
            EXPECT_EQ(coveredColumns(image, row), Runs({{c.firstColumn, c.lastColumn}})) << c.name << " row " << row;
        for (int column : {c.firstColumn, (c.firstColumn + c.lastColumn) / 2, c.lastColumn})
            EXPECT_EQ(coveredRows(image, column), Runs({{61, 66}})) << c.name << " column " << column;
        expectPixel(image, (c.firstColumn + c.lastColumn) / 2, 63, color, c.name);
    }
}

TEST(AnalyticPixels, PeriodicCurvesCloseThroughTheirKnownPoints) {
    // Control points on the square with corners (32, 32) and (96, 96), in
    // order around it; the closing span runs from the last point back to the
    // first, up the left side.
    const std::vector<glm::vec3> corners = {at(32, 32), at(96, 32), at(96, 96), at(32, 96)};
    const glm::vec3 color(0.2f, 0.7f, 0.4f);

    // Linear: the square itself. Row 64 crosses the right side and the closing left side.
    Image linear =
        renderFlat(strand("/loop", CurveType::Linear, CurveBasis::Bezier, CurveWrap::Periodic, {4}, corners, color));
    EXPECT_EQ(coveredColumns(linear, 64), Runs({{29, 34}, {93, 98}}));
    expectPixel(linear, 31, 64, color, "linear closing side");
    expectEmpty(linear, 64, 64, "linear inside");

    // Bezier: four straight cubic spans with handles at a quarter and three
    // quarters of each side, the last closing on the first point.
    std::vector<glm::vec3> bezierPoints;
    for (size_t side = 0; side < 4; ++side) {
        glm::vec3 from = corners[side], to = corners[(side + 1) % 4];
        bezierPoints.insert(bezierPoints.end(), {from, from + 0.25f * (to - from), from + 0.75f * (to - from)});
    }
    Image bezier = renderFlat(
        strand("/loop", CurveType::Cubic, CurveBasis::Bezier, CurveWrap::Periodic, {12}, bezierPoints, color));
    EXPECT_EQ(coveredColumns(bezier, 64), Runs({{29, 34}, {93, 98}}));
    expectPixel(bezier, 31, 64, color, "bezier closing side");
    expectEmpty(bezier, 64, 64, "bezier inside");

    // catmullRom passes through every control point; the closing span's
    // middle is 9/16 (P3 + P0) - 1/16 (P2 + P1) = (24, 64), where the loop
    // runs vertically: covered 3 px either side of x = 24.
    Image catmullRom =
        renderFlat(strand("/loop", CurveType::Cubic, CurveBasis::CatmullRom, CurveWrap::Periodic, {4}, corners, color));
    expectPixel(catmullRom, 32, 32, color, "catmullRom through its first point");
    expectPixel(catmullRom, 95, 95, color, "catmullRom through its third point");
    expectPixel(catmullRom, 24, 64, color, "catmullRom closing span's middle");
    expectEmpty(catmullRom, 20, 64, "left of the closing span");
    expectEmpty(catmullRom, 28, 64, "right of the closing span");
    expectEmpty(catmullRom, 64, 64, "catmullRom inside");

    // bspline passes (P[i-1] + 4 P[i] + P[i+1]) / 6 = (42.7, 42.7) near the
    // first corner, not the corner itself; the closing span's middle is
    // 23/48 (P3 + P0) + 1/48 (P2 + P1) = (34.7, 64).
    Image bspline =
        renderFlat(strand("/loop", CurveType::Cubic, CurveBasis::Bspline, CurveWrap::Periodic, {4}, corners, color));
    expectPixel(bspline, 42, 42, color, "bspline near its first point");
    expectEmpty(bspline, 32, 32, "bspline's first control point");
    expectPixel(bspline, 34, 64, color, "bspline closing span's middle");
    expectEmpty(bspline, 30, 64, "left of the closing span");
    expectEmpty(bspline, 38, 64, "right of the closing span");
    expectEmpty(bspline, 64, 64, "bspline inside");
}

TEST(AnalyticPixels, ColourPrimvarsInterpolateAsTheirInterpolationSays) {
    // A catmullRom strand along the row boundary y = 64 with control points
    // 32 px apart at x = -16, 16, 48, 80, 112: spans 16..48 and 48..80, where
    // x is linear in the span parameter u (uniform collinear points).
    std::vector<glm::vec3> points;
    for (double x : {-16.0, 16.0, 48.0, 80.0, 112.0}) points.push_back(at(x, 64.0));
    CurvesPrim prim =
        strand("/curve", CurveType::Cubic, CurveBasis::CatmullRom, CurveWrap::Nonperiodic, {5}, points, {});
    // Each column's pixel centre on the strand: its span and u on it.
    struct Sample {
        int column, span;
        float u;
    };
    std::vector<Sample> samples;
    for (int column : {16, 20, 31, 47, 48, 59, 79}) {
        double spans = (column + 0.5 - 16.0) / 32.0;
        samples.push_back({column, int(spans), float(spans - std::floor(spans))});
    }

    // vertex: one colour per control point, through the Catmull-Rom weights.
    const std::vector<glm::vec3> vertexColors = {
        {0.2f, 0.5f, 0.3f}, {0.8f, 0.2f, 0.6f}, {0.3f, 0.7f, 0.2f}, {0.7f, 0.4f, 0.8f}, {0.4f, 0.6f, 0.5f}};
    prim.primvars["displayColor"] = displayColors(Interpolation::Vertex, vertexColors);
    Image vertex = renderFlat(prim);
    for (const Sample& sample : samples) {
        std::array<float, 4> w = catmullRomWeights(sample.u);
        glm::vec3 expected(0.0f);
        for (int k = 0; k < 4; ++k) expected += w[size_t(k)] * vertexColors[size_t(sample.span + k)];
        expectPixel(vertex, sample.column, 63, expected, "vertex");
    }

    // varying: one colour per span end (x = 16, 48, 80), linear between them.
    const std::vector<glm::vec3> varyingColors = {{0.9f, 0.1f, 0.2f}, {0.1f, 0.8f, 0.3f}, {0.2f, 0.3f, 0.9f}};
    prim.primvars["displayColor"] = displayColors(Interpolation::Varying, varyingColors);
    Image varying = renderFlat(prim);
    for (const Sample& sample : samples)
        expectPixel(varying, sample.column, 63,
                    glm::mix(varyingColors[size_t(sample.span)], varyingColors[size_t(sample.span + 1)], sample.u),
                    "varying");

    // constant: one colour everywhere.
    prim.primvars["displayColor"] = displayColors(Interpolation::Constant, {{0.35f, 0.55f, 0.75f}});
    Image constant = renderFlat(prim);
    for (const Sample& sample : samples) expectPixel(constant, sample.column, 63, {0.35f, 0.55f, 0.75f}, "constant");

    // uniform: one colour per curve; a second curve 32 px lower.
    prim.curveVertexCounts = {5, 5};
    for (double x : {-16.0, 16.0, 48.0, 80.0, 112.0}) prim.points.push_back(at(x, 96.0));
    prim.primvars["displayColor"] = displayColors(Interpolation::Uniform, {{0.9f, 0.6f, 0.1f}, {0.1f, 0.4f, 0.9f}});
    Image uniform = renderFlat(prim);
    for (const Sample& sample : samples) {
        expectPixel(uniform, sample.column, 63, {0.9f, 0.6f, 0.1f}, "first curve");
        expectPixel(uniform, sample.column, 95, {0.1f, 0.4f, 0.9f}, "second curve");
    }
}

TEST(AnalyticPixels, OpacityGivesPreMultipliedColourAndAlpha) {
    // The same straight strand (x 16 to 112 at y 64), translucent: it blends,
    // over nothing, so each pixel is (colour x opacity, opacity), on the same
    // 6 rows. Vertex opacity 0.2 at x = 16 to 0.8 at x = 112 (linear curve:
    // linear in x).
    const glm::vec3 color(0.9f, 0.5f, 0.2f);
    CurvesPrim translucent = strand("/curve", CurveType::Linear, CurveBasis::Bezier, CurveWrap::Nonperiodic, {2},
                                    {at(16, 64), at(112, 64)}, color);
    translucent.primvars["displayOpacity"] = authoredPrimvar("displayOpacity", Interpolation::Constant, 1, {0.4f});
    Scene scene;
    scene.setCurves(translucent);
    Image constant = renderFlat(scene, "binSorted");
    EXPECT_EQ(coveredRows(constant, 40), Runs({{61, 66}}));
    EXPECT_EQ(coveredColumns(constant, 63), Runs({{16, 111}}));
    for (int column : {16, 40, 111}) expectPixel(constant, column, 63, color, "opacity 0.4", 0.4f);

    translucent.primvars["displayOpacity"] = authoredPrimvar("displayOpacity", Interpolation::Vertex, 1, {0.2f, 0.8f});
    scene.setCurves(translucent);
    Image ramp = renderFlat(scene, "binSorted");
    for (int column : {16, 40, 63, 111}) {
        float opacity = 0.2f + 0.6f * (float(column) + 0.5f - 16.0f) / 96.0f;
        expectPixel(ramp, column, 63, color, "opacity ramp", opacity);
    }
}

namespace {

// A layer read by the embedded reader, as hdhair-record reads a stage.
Scene readLayer(const std::string& text) {
    std::unique_ptr<usda::Stage> stage = usda::Stage::openFromString(text, "analytic.usda");
    Scene scene;
    Diagnostics diagnostics;
    usda::readScene(*stage, 0.0, scene, diagnostics);
    EXPECT_TRUE(diagnostics.warnings().empty()) << diagnostics.warnings().front().message;
    return scene;
}

}  // namespace


TEST(AnalyticPixels, InstancesLandWhereTheirTransformsPutThem) {
    // A prototype strand from x = -0.5 to 0.5, 6 px wide, instanced twice:
    // moved up by 0.5 (pixels 48..80 at y 48), and moved down by 1 and scaled
    // by 2 (pixels 32..96 at y 96, 12 px wide). The class itself is not drawn.
    Scene scene = readLayer(R"(#usda 1.0
class Xform "Tuft"
{
    def BasisCurves "strand"
    {
        uniform token type = "linear"
        int[] curveVertexCounts = [2]
        point3f[] points = [(-0.5, 0, 0), (0.5, 0, 0)]
        float[] widths = [0.1875] (interpolation = "constant")
        color3f[] primvars:displayColor = [(0.9, 0.3, 0.1)] (interpolation = "constant")
    }
}

def Xform "above" (
    instanceable = true
    prepend references = </Tuft>
)
{
    double3 xformOp:translate = (0, 0.5, 0)
    uniform token[] xformOpOrder = ["xformOp:translate"]
}

def Xform "below" (
    instanceable = true
    prepend references = </Tuft>
)
{
    double3 xformOp:translate = (0, -1, 0)
    float3 xformOp:scale = (2, 2, 2)
    uniform token[] xformOpOrder = ["xformOp:translate", "xformOp:scale"]
}
)");
    ASSERT_EQ(scene.curves().size(), 2u) << "two instances, no prototype";
    Image image = renderFlat(scene);
    EXPECT_EQ(coveredColumns(image, 47), Runs({{48, 79}}));
    EXPECT_EQ(coveredRows(image, 64), Runs({{45, 50}, {90, 101}}));
    EXPECT_EQ(coveredColumns(image, 96), Runs({{32, 95}}));
    expectPixel(image, 64, 47, {0.9f, 0.3f, 0.1f}, "above");
    expectPixel(image, 40, 97, {0.9f, 0.3f, 0.1f}, "below");
}

TEST(AnalyticPixels, TransformsMoveScaleAndTurnStrands) {
    // "moved/scaled": a strand from x = -1 to 1, 12 px wide, scaled by 0.5
    // and moved by (0.5, 0.25): x 0 to 1 (pixels 64..96) at y 0.25 (pixel
    // 56), 6 px wide. "turned": a strand from x = -0.5 to 0.5 turned 90
    // degrees about Z and moved by (-1, 0): vertical at x = -1 (pixel 32)
    // from y = -0.5 to 0.5 (pixels 48..80).
    Scene scene = readLayer(R"(#usda 1.0
def Xform "moved"
{
    double3 xformOp:translate = (0.5, 0.25, 0)
    uniform token[] xformOpOrder = ["xformOp:translate"]

    def Xform "scaled"
    {
        float3 xformOp:scale = (0.5, 0.5, 0.5)
        uniform token[] xformOpOrder = ["xformOp:scale"]

        def BasisCurves "strand"
        {
            uniform token type = "linear"
            int[] curveVertexCounts = [2]
            point3f[] points = [(-1, 0, 0), (1, 0, 0)]
            float[] widths = [0.375] (interpolation = "constant")
            color3f[] primvars:displayColor = [(0.2, 0.4, 0.9)] (interpolation = "constant")
        }
    }
}

def Xform "turned"
{
    double3 xformOp:translate = (-1, 0, 0)
    float3 xformOp:rotateXYZ = (0, 0, 90)
    uniform token[] xformOpOrder = ["xformOp:translate", "xformOp:rotateXYZ"]

    def BasisCurves "strand"
    {
        uniform token type = "linear"
        int[] curveVertexCounts = [2]
        point3f[] points = [(-0.5, 0, 0), (0.5, 0, 0)]
        float[] widths = [0.1875] (interpolation = "constant")
        color3f[] primvars:displayColor = [(0.6, 0.8, 0.2)] (interpolation = "constant")
    }
}
)");
    ASSERT_EQ(scene.curves().size(), 2u);
    Image image = renderFlat(scene);
    EXPECT_EQ(coveredColumns(image, 55), Runs({{29, 34}, {64, 95}}));
    EXPECT_EQ(coveredRows(image, 80), Runs({{53, 58}}));
    EXPECT_EQ(coveredColumns(image, 64), Runs({{29, 34}}));
    EXPECT_EQ(coveredRows(image, 31), Runs({{48, 79}}));
    expectPixel(image, 80, 56, {0.2f, 0.4f, 0.9f}, "moved and scaled");
    expectPixel(image, 32, 70, {0.6f, 0.8f, 0.2f}, "turned");
}
