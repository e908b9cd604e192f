#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/curves/CurveTopology.h"
#include "hdHair/curves/PrimvarResolution.h"

using namespace hdhair;

namespace {

const char* kPath = "/World/hair";

CurveKind cubic(CurveBasis basis, CurveWrap wrap) { return CurveKind{CurveType::Cubic, basis, wrap}; }
CurveKind linear(CurveWrap wrap) { return CurveKind{CurveType::Linear, CurveBasis::Bezier, wrap}; }

// `count` elements of `tupleSize` components; element e component c is e + c/10.
Primvar makePrimvar(size_t count, int tupleSize, Interpolation interpolation, bool authored = true) {
    Primvar primvar;
    primvar.tupleSize = tupleSize;
    primvar.interpolation = interpolation;
    primvar.interpolationAuthored = authored;
    for (size_t e = 0; e < count; ++e)
        for (int c = 0; c < tupleSize; ++c)
            primvar.values.push_back(static_cast<float>(e) + 0.1f * static_cast<float>(c));
    return primvar;
}

// These values, with an authored interpolation.
Primvar primvarOf(Interpolation interpolation, std::vector<float> values, int tupleSize = 1) {
    Primvar primvar;
    primvar.tupleSize = tupleSize;
    primvar.interpolation = interpolation;
    primvar.interpolationAuthored = true;
    primvar.values = std::move(values);
    return primvar;
}

std::string fullText(const Diagnostic& d) { return d.where + ": " + d.message; }

// `widths` resolves to the constant fallback width with the one warning `expected` ("where: message").
void expectFallbackWidth(const Primvar& widths, const CurveTopology& topology, const std::string& expected) {
    Diagnostics diagnostics;
    const ResolvedPrimvar result = resolvePrimvar(widths, topology, kFallbackWidth, kPath, "widths", diagnostics);
    EXPECT_EQ(result.interpolation, Interpolation::Constant);
    EXPECT_EQ(result.values, kFallbackWidth);
    ASSERT_EQ(diagnostics.warningCount(), 1u);
    EXPECT_EQ(fullText(diagnostics.warnings()[0]), expected);
}

}  // namespace

// --- Counts (as CurveTopology.h's sources define them), written out by hand --

TEST(CurveTopology, CountsFollowUsdImplementedRules) {
    struct Row {
        CurveKind kind;
        int n, segments, varying, spanEnds;
        bool valid;
    };
    const CurveWrap np = CurveWrap::Nonperiodic, pe = CurveWrap::Periodic, pi = CurveWrap::Pinned;
    const CurveBasis bz = CurveBasis::Bezier, bs = CurveBasis::Bspline, cr = CurveBasis::CatmullRom;
    const Row rows[] = {
        // cubic nonperiodic: segments (n-4)/vstep+1, varying max(n-4,0)/vstep+2
        {cubic(bz, np), 4, 1, 2, 2, true},
        {cubic(bz, np), 7, 2, 3, 3, true},
        {cubic(bs, np), 4, 1, 2, 2, true},
        {cubic(bs, np), 6, 3, 4, 4, true},
        {cubic(cr, np), 5, 2, 3, 3, true},
        // under-length / off-step (HdSt clamps): bunnyCurves.usda's 5, 8, 9
        {cubic(bz, np), 5, 1, 2, 2, false},
        {cubic(bz, np), 8, 2, 3, 3, false},
        {cubic(bz, np), 9, 2, 3, 3, false},
        {cubic(bs, np), 3, 1, 2, 2, false},
        {cubic(bs, np), 2, 1, 2, 2, false},
        {cubic(bs, np), 1, 0, 2, 2, false},
        {cubic(bs, np), 0, 0, 0, 0, false},
        // cubic periodic: n/vstep segments and varying values (at least 1)
        {cubic(bz, pe), 6, 2, 2, 2, true},
        {cubic(bz, pe), 3, 1, 1, 1, true},
        {cubic(bz, pe), 2, 1, 1, 1, false},
        {cubic(bz, pe), 7, 2, 2, 2, false},
        {cubic(bs, pe), 5, 5, 5, 5, true},
        {cubic(cr, pe), 4, 4, 4, 4, true},
        // pinned: bezier as nonperiodic; bspline/catmullRom n-1 spans, varying
        // authored at the nonperiodic size, resolved to n span ends
        {cubic(bz, pi), 7, 2, 3, 3, true},
        {cubic(bz, pi), 5, 1, 2, 2, false},
        {cubic(bs, pi), 5, 4, 3, 5, true},
        {cubic(cr, pi), 5, 4, 3, 5, true},
        {cubic(cr, pi), 4, 3, 2, 4, true},
        {cubic(bs, pi), 3, 2, 2, 3, true},
        {cubic(cr, pi), 2, 1, 2, 2, true},
        {cubic(cr, pi), 1, 0, 2, 2, false},
        // linear: n-1 (nonperiodic, pinned) or n (periodic) segments, n varying
        {linear(np), 2, 1, 2, 2, true},
        {linear(np), 5, 4, 5, 5, true},
        {linear(np), 1, 0, 1, 1, false},
        {linear(pi), 3, 2, 3, 3, true},
        {linear(pe), 3, 3, 3, 3, true},
        {linear(pe), 2, 2, 2, 2, false},
    };
    for (const Row& row : rows) {
        SCOPED_TRACE(toString(row.kind) + " n=" + std::to_string(row.n));
        EXPECT_EQ(segmentCount(row.kind, row.n), row.segments);
        EXPECT_EQ(varyingCount(row.kind, row.n), row.varying);
        EXPECT_EQ(spanEndCount(row.kind, row.n), row.spanEnds);
        EXPECT_EQ(isValidVertexCount(row.kind, row.n), row.valid);
    }
}

TEST(CurveTopology, OffsetsArePrefixSums) {
    CurvesPrim prim;
    prim.basis = CurveBasis::Bezier;
    prim.curveVertexCounts = {4, 7, -2, 10};
    const CurveTopology topology(prim);
    ASSERT_EQ(topology.curveCount(), 4u);
    EXPECT_EQ(topology.vertexCounts[2], 0);  // a negative count reads as empty
    EXPECT_EQ(topology.vertexOffsets, (std::vector<size_t>{0, 4, 11, 11, 21}));
    EXPECT_EQ(topology.varyingOffsets, (std::vector<size_t>{0, 2, 5, 5, 9}));
    EXPECT_EQ(topology.segmentOffsets, (std::vector<size_t>{0, 1, 3, 3, 6}));
    EXPECT_EQ(topology.segmentTotal(), 6u);

    const CurveTopology empty;
    EXPECT_EQ(empty.curveCount(), 0u);
    EXPECT_EQ(empty.vertexTotal(), 0u);
}

// --- Every interpolation x basis x wrap with correctly sized data -------------

using ResolutionCase = std::tuple<Interpolation, int /*basis, 3 = linear*/, CurveWrap>;

class CorrectSizes : public ::testing::TestWithParam<ResolutionCase> {};

TEST_P(CorrectSizes, ResolveWithoutWarningsToTheNeededCount) {
    const auto [interpolation, basisIndex, wrap] = GetParam();
    const CurveKind kind = basisIndex == 3 ? linear(wrap) : cubic(static_cast<CurveBasis>(basisIndex), wrap);
    // Three valid curves of different lengths for this kind.
    std::vector<int> counts;
    for (int n = 0; counts.size() < 3 && n < 40; ++n)
        if (isValidVertexCount(kind, n) && (counts.empty() || n > counts.back() + 1)) counts.push_back(n);
    ASSERT_EQ(counts.size(), 3u);
    const CurveTopology topology(kind, counts);

    size_t authored = 0, resolved = 0;
    switch (interpolation) {
    case Interpolation::Constant: authored = resolved = 1; break;
    case Interpolation::Uniform: authored = resolved = 3; break;
    case Interpolation::Vertex: authored = resolved = topology.vertexTotal(); break;
    case Interpolation::Varying:
    case Interpolation::FaceVarying:
        authored = topology.varyingTotal();
        resolved = topology.spanEndTotal();
        break;
    }
    const Primvar primvar = makePrimvar(authored, 3, interpolation);
    Diagnostics diagnostics;
    const ResolvedPrimvar result =
        resolvePrimvar(primvar, topology, kFallbackDisplayColor, kPath, "displayColor", diagnostics);
    EXPECT_EQ(diagnostics.warningCount(), 0u);
    const Interpolation expectedInterpolation =
        interpolation == Interpolation::FaceVarying ? Interpolation::Varying : interpolation;
    EXPECT_EQ(result.interpolation, expectedInterpolation);
    EXPECT_EQ(result.tupleSize, 3);
    ASSERT_EQ(result.elementCount(), resolved);

    if (kind.hasPhantomEnds() && expectedInterpolation == Interpolation::Varying) {
        // Each curve's authored values, with its end values repeated for the
        // two phantom-end spans when it has them (n >= 4).
        size_t source = 0;
        for (size_t i = 0; i < 3; ++i) {
            const size_t m = topology.varyingOffsets[i + 1] - topology.varyingOffsets[i];
            const size_t ends = static_cast<size_t>(topology.spanEndCount(i));
            const float* values = result.element(topology.spanEndOffsets[i]);
            const size_t pad = ends == m ? 0 : 1;
            ASSERT_EQ(ends, m + 2 * pad);
            EXPECT_FLOAT_EQ(values[0], static_cast<float>(source));
            for (size_t k = 0; k < m; ++k) EXPECT_FLOAT_EQ(values[3 * (k + pad)], static_cast<float>(source + k));
            EXPECT_FLOAT_EQ(values[3 * (ends - 1)], static_cast<float>(source + m - 1));
            source += m;
        }
    } else {
        EXPECT_EQ(result.values, primvar.values);
    }
}

std::string caseName(const ::testing::TestParamInfo<ResolutionCase>& info) {
    static const char* const kBases[] = {"bezier", "bspline", "catmullRom", "linear"};
    return std::string(toString(std::get<0>(info.param))) + "_" + kBases[std::get<1>(info.param)] + "_" +
           toString(std::get<2>(info.param));
}

INSTANTIATE_TEST_SUITE_P(
    AllCombinations, CorrectSizes,
    ::testing::Combine(::testing::Values(Interpolation::Constant, Interpolation::Uniform, Interpolation::Varying,
                                         Interpolation::Vertex, Interpolation::FaceVarying),
                       ::testing::Values(0, 1, 2, 3),  // bezier, bspline, catmullRom, linear
                       ::testing::Values(CurveWrap::Nonperiodic, CurveWrap::Periodic, CurveWrap::Pinned)),
    caseName);

// --- Sizes USD tolerates ------------------------------------------------------

TEST(PrimvarResolution, PinnedVaryingAcceptsTheImplementedSize) {
    const CurveTopology topology(cubic(CurveBasis::Bspline, CurveWrap::Pinned), {5, 2, 3});
    ASSERT_EQ(topology.varyingTotal(), 3u + 2u + 2u);
    const Primvar widths = primvarOf(Interpolation::Varying, {1, 2, 3, 4, 5, 6, 8});
    Diagnostics diagnostics;
    const ResolvedPrimvar result = resolvePrimvar(widths, topology, kFallbackWidth, kPath, "widths", diagnostics);
    EXPECT_EQ(diagnostics.warningCount(), 0u);
    EXPECT_EQ(result.interpolation, Interpolation::Varying);
    // n = 5: the phantom-end spans repeat the end values; n = 2: already one
    // per span end; n = 3: two values spread over three span ends.
    EXPECT_EQ(result.values, (std::vector<float>{1, 1, 2, 3, 3, 4, 5, 6, 7, 8}));
}

TEST(PrimvarResolution, PinnedVaryingAcceptsOneValuePerVertex) {
    const CurveTopology topology(cubic(CurveBasis::CatmullRom, CurveWrap::Pinned), {5, 2});
    const Primvar widths = primvarOf(Interpolation::Varying, {1, 2, 3, 4, 5, 6, 7});
    Diagnostics diagnostics;
    const ResolvedPrimvar result = resolvePrimvar(widths, topology, kFallbackWidth, kPath, "widths", diagnostics);
    EXPECT_EQ(diagnostics.warningCount(), 0u);
    EXPECT_EQ(result.values, widths.values);
}

TEST(PrimvarResolution, PinnedVaryingOfAnotherSizeNamesBothAcceptedSizes) {
    const CurveTopology topology(cubic(CurveBasis::CatmullRom, CurveWrap::Pinned), {5, 5});
    expectFallbackWidth(
        primvarOf(Interpolation::Varying, {1, 2, 3, 4, 5, 6, 7, 8}), topology,
        "/World/hair.widths: varying interpolation needs 6 values (or 10), found 8; using the fallback 1");
}

TEST(PrimvarResolution, LinearPeriodicVaryingAcceptsNPlusOne) {
    const CurveTopology topology(linear(CurveWrap::Periodic), {3, 4});
    const Primvar opacity =
        primvarOf(Interpolation::Varying, {1, 2, 3, 1, 4, 5, 6, 7, 4});  // each curve closes on its first value
    Diagnostics diagnostics;
    const ResolvedPrimvar result =
        resolvePrimvar(opacity, topology, kFallbackDisplayOpacity, kPath, "displayOpacity", diagnostics);
    EXPECT_EQ(diagnostics.warningCount(), 0u);
    EXPECT_EQ(result.values, (std::vector<float>{1, 2, 3, 4, 5, 6, 7}));
}

TEST(PrimvarResolution, UnderLengthCurvesUseTheImplementedCounts) {
    // bunnyCurves.usda authors bezier counts 8, 9 and 5.
    const CurveTopology topology(cubic(CurveBasis::Bezier, CurveWrap::Nonperiodic), {8, 9, 5});
    Diagnostics diagnostics;
    const ResolvedPrimvar vertex = resolvePrimvar(makePrimvar(22, 1, Interpolation::Vertex), topology, kFallbackWidth,
                                                  kPath, "widths", diagnostics);
    const ResolvedPrimvar varying = resolvePrimvar(makePrimvar(3 + 3 + 2, 1, Interpolation::Varying), topology,
                                                   kFallbackWidth, kPath, "widths", diagnostics);
    EXPECT_EQ(diagnostics.warningCount(), 0u);
    EXPECT_EQ(vertex.elementCount(), 22u);
    EXPECT_EQ(varying.interpolation, Interpolation::Varying);
    EXPECT_EQ(varying.elementCount(), 8u);
}

// --- Size-1 data is constant --------------------------------------------------

TEST(PrimvarResolution, OneValueWithoutInterpolationIsConstant) {
    // basicCurves.usda: `float[] widths = [0.2]`, vertex by default, no metadata.
    const CurveTopology topology(cubic(CurveBasis::Bezier, CurveWrap::Nonperiodic), {4, 7});
    Primvar widths;
    widths.values = {0.2f};
    widths.interpolation = Interpolation::Vertex;
    widths.interpolationAuthored = false;
    Diagnostics diagnostics;
    const ResolvedPrimvar result = resolvePrimvar(widths, topology, kFallbackWidth, kPath, "widths", diagnostics);
    EXPECT_EQ(diagnostics.warningCount(), 0u);
    EXPECT_EQ(result.interpolation, Interpolation::Constant);
    EXPECT_EQ(result.values, std::vector<float>{0.2f});
}

TEST(PrimvarResolution, OneValueOfAnyPerElementInterpolationIsConstant) {
    const CurveTopology topology(cubic(CurveBasis::CatmullRom, CurveWrap::Periodic), {4, 5});
    for (Interpolation interpolation :
         {Interpolation::Uniform, Interpolation::Varying, Interpolation::Vertex, Interpolation::FaceVarying}) {
        SCOPED_TRACE(toString(interpolation));
        Primvar color = makePrimvar(1, 3, interpolation);
        Diagnostics diagnostics;
        const ResolvedPrimvar result =
            resolvePrimvar(color, topology, kFallbackDisplayColor, kPath, "displayColor", diagnostics);
        EXPECT_EQ(diagnostics.warningCount(), 0u);
        EXPECT_EQ(result.interpolation, Interpolation::Constant);
        EXPECT_EQ(result.values, color.values);
    }
}

TEST(PrimvarResolution, ConstantWithSeveralValuesKeepsTheFirst) {
    const CurveTopology topology(cubic(CurveBasis::Bezier, CurveWrap::Nonperiodic), {4});
    Diagnostics diagnostics;
    const ResolvedPrimvar result = resolvePrimvar(makePrimvar(4, 3, Interpolation::Constant, false), topology,
                                                  kFallbackDisplayColor, kPath, "displayColor", diagnostics);
    EXPECT_EQ(result.values, (std::vector<float>{0.0f, 0.1f, 0.2f}));
    ASSERT_EQ(diagnostics.warningCount(), 1u);
    EXPECT_EQ(fullText(diagnostics.warnings()[0]),
              "/World/hair.primvars:displayColor: constant interpolation needs 1 value, found 4; using the first");
}

// --- Indexed primvars ---------------------------------------------------------

TEST(PrimvarResolution, IndicesAreFollowed) {
    const CurveTopology topology(cubic(CurveBasis::Bspline, CurveWrap::Nonperiodic), {4, 4});
    Primvar color = primvarOf(Interpolation::Uniform, {1, 0, 0, 0, 1, 0}, 3);
    color.indices = {1, 0};
    Diagnostics diagnostics;
    const ResolvedPrimvar result =
        resolvePrimvar(color, topology, kFallbackDisplayColor, kPath, "displayColor", diagnostics);
    EXPECT_EQ(diagnostics.warningCount(), 0u);
    EXPECT_EQ(result.interpolation, Interpolation::Uniform);
    EXPECT_EQ(result.values, (std::vector<float>{0, 1, 0, 1, 0, 0}));
}

TEST(PrimvarResolution, OutOfRangeIndexUsesTheFallbackForThatElement) {
    const CurveTopology topology(cubic(CurveBasis::Bezier, CurveWrap::Nonperiodic), {4});
    Primvar widths = primvarOf(Interpolation::Vertex, {0.5f, 0.25f});
    widths.indices = {0, 1, 7, -1};
    Diagnostics diagnostics;
    const ResolvedPrimvar result = resolvePrimvar(widths, topology, kFallbackWidth, kPath, "widths", diagnostics);
    EXPECT_EQ(result.interpolation, Interpolation::Vertex);
    EXPECT_EQ(result.values, (std::vector<float>{0.5f, 0.25f, 1.0f, 1.0f}));
    ASSERT_EQ(diagnostics.warningCount(), 1u);
    EXPECT_EQ(fullText(diagnostics.warnings()[0]),
              "/World/hair.widths: 2 indices are out of range for 2 values (first: indices[2] = 7); using the "
              "fallback 1 for them");
}

TEST(PrimvarResolution, IndexedVertexDataTooLongIsTruncated) {
    const CurveTopology topology(cubic(CurveBasis::Bezier, CurveWrap::Nonperiodic), {4});
    Primvar widths = primvarOf(Interpolation::Vertex, {1, 2, 3});
    widths.indices = {0, 1, 2, 1, 0, 2};
    Diagnostics diagnostics;
    const ResolvedPrimvar result = resolvePrimvar(widths, topology, kFallbackWidth, kPath, "widths", diagnostics);
    EXPECT_EQ(diagnostics.warningCount(), 0u);
    EXPECT_EQ(result.values, (std::vector<float>{1, 2, 3, 2}));
}

// --- Wrong data -------------------------------------------------------------

TEST(PrimvarResolution, WrongCountWarnsAndUsesTheFallback) {
    const CurveTopology topology(cubic(CurveBasis::Bezier, CurveWrap::Nonperiodic), {4, 4, 4});
    Diagnostics diagnostics;
    const ResolvedPrimvar color = resolvePrimvar(makePrimvar(7, 3, Interpolation::Vertex), topology,
                                                 kFallbackDisplayColor, kPath, "displayColor", diagnostics);
    EXPECT_EQ(color.interpolation, Interpolation::Constant);
    EXPECT_EQ(color.values, kFallbackDisplayColor);
    const ResolvedPrimvar width = resolvePrimvar(makePrimvar(2, 1, Interpolation::Uniform), topology, kFallbackWidth,
                                                 kPath, "widths", diagnostics);
    EXPECT_EQ(width.values, kFallbackWidth);
    const ResolvedPrimvar opacity = resolvePrimvar(makePrimvar(0, 1, Interpolation::Constant), topology,
                                                   kFallbackDisplayOpacity, kPath, "displayOpacity", diagnostics);
    EXPECT_EQ(opacity.values, kFallbackDisplayOpacity);
    const ResolvedPrimvar indexedTooShort = [&] {
        Primvar p = makePrimvar(2, 1, Interpolation::Vertex);
        p.indices = {0, 1, 1};
        return resolvePrimvar(p, topology, kFallbackWidth, kPath, "widths", diagnostics);
    }();
    EXPECT_EQ(indexedTooShort.values, kFallbackWidth);

    const std::vector<Diagnostic> warnings = diagnostics.warnings();
    ASSERT_EQ(warnings.size(), 4u);
    EXPECT_EQ(warnings[0].where, "/World/hair.primvars:displayColor");
    EXPECT_EQ(fullText(warnings[0]),
              "/World/hair.primvars:displayColor: vertex interpolation needs 12 values, found 7; using the fallback "
              "(0.5, 0.5, 0.5)");
    EXPECT_EQ(fullText(warnings[1]),
              "/World/hair.widths: uniform interpolation needs 3 values, found 2; using the fallback 1");
    EXPECT_EQ(
        fullText(warnings[2]),
        "/World/hair.primvars:displayOpacity: constant interpolation needs 1 value, found 0; using the fallback 1");
    EXPECT_EQ(fullText(warnings[3]),
              "/World/hair.widths: vertex interpolation needs 12 values, found 3; using the fallback 1");
}

TEST(PrimvarResolution, FaceVaryingOfTheWrongSizeNamesFaceVarying) {
    const CurveTopology topology(cubic(CurveBasis::Bspline, CurveWrap::Nonperiodic), {5});
    Diagnostics diagnostics;
    resolvePrimvar(makePrimvar(5, 1, Interpolation::FaceVarying), topology, kFallbackWidth, kPath, "widths",
                   diagnostics);
    ASSERT_EQ(diagnostics.warningCount(), 1u);
    EXPECT_EQ(diagnostics.warnings()[0].message,
              "faceVarying interpolation needs 3 values, found 5; using the fallback 1");
}

TEST(PrimvarResolution, NonFiniteValuesAreReplacedByTheFallback) {
    const CurveTopology topology(cubic(CurveBasis::CatmullRom, CurveWrap::Nonperiodic), {4});
    Primvar color = makePrimvar(4, 3, Interpolation::Vertex);
    color.values[4] = std::numeric_limits<float>::quiet_NaN();
    color.values[9] = std::numeric_limits<float>::infinity();
    Diagnostics diagnostics;
    const ResolvedPrimvar result =
        resolvePrimvar(color, topology, kFallbackDisplayColor, kPath, "displayColor", diagnostics);
    EXPECT_EQ(result.interpolation, Interpolation::Vertex);
    EXPECT_EQ(result.values,
              (std::vector<float>{0.0f, 0.1f, 0.2f, 0.5f, 0.5f, 0.5f, 2.0f, 2.1f, 2.2f, 0.5f, 0.5f, 0.5f}));
    ASSERT_EQ(diagnostics.warningCount(), 1u);
    EXPECT_EQ(fullText(diagnostics.warnings()[0]),
              "/World/hair.primvars:displayColor: 2 elements are not finite (first: element 1); using the fallback "
              "(0.5, 0.5, 0.5) for them");
}

TEST(PrimvarResolution, WrongTupleSizeWarnsAndUsesTheFallback) {
    const CurveTopology topology(cubic(CurveBasis::Bezier, CurveWrap::Nonperiodic), {4});
    Primvar widths = makePrimvar(4, 3, Interpolation::Vertex);
    widths.typeName = "float3[]";
    expectFallbackWidth(
        widths, topology,
        "/World/hair.widths: expects 1 component per element, found 3 (float3[]); using the fallback 1");
}

TEST(PrimvarResolution, PartialTrailingElementIsIgnored) {
    const CurveTopology topology(cubic(CurveBasis::Bezier, CurveWrap::Nonperiodic), {4});
    Primvar color = makePrimvar(4, 3, Interpolation::Vertex);
    color.values.push_back(9.0f);
    Diagnostics diagnostics;
    const ResolvedPrimvar result =
        resolvePrimvar(color, topology, kFallbackDisplayColor, kPath, "displayColor", diagnostics);
    EXPECT_EQ(result.elementCount(), 4u);
    ASSERT_EQ(diagnostics.warningCount(), 1u);
    EXPECT_EQ(diagnostics.warnings()[0].message, "13 floats are not whole 3-component elements; ignoring the last 1");
}

// --- Names and unauthored primvars ------------------------------------------

TEST(PrimvarResolution, MessagesUseUsdAttributeNames) {
    EXPECT_EQ(attributeName("widths"), "widths");
    EXPECT_EQ(attributeName("normals"), "normals");
    EXPECT_EQ(attributeName("displayColor"), "primvars:displayColor");
    EXPECT_EQ(attributeName("hair:melanin"), "primvars:hair:melanin");
}

TEST(PrimvarResolution, UnauthoredPrimvarsResolveToTheirFallbacks) {
    CurvesPrim prim;
    prim.path = kPath;
    prim.curveVertexCounts = {4};
    const CurveTopology topology(prim);
    Diagnostics diagnostics;
    EXPECT_EQ(resolvePrimvar(prim, topology, "widths", kFallbackWidth, diagnostics).values, std::vector<float>{1.0f});
    EXPECT_EQ(resolvePrimvar(prim, topology, "displayColor", kFallbackDisplayColor, diagnostics).values,
              (std::vector<float>{0.5f, 0.5f, 0.5f}));
    const ResolvedPrimvar opacity =
        resolvePrimvar(prim, topology, "displayOpacity", kFallbackDisplayOpacity, diagnostics);
    EXPECT_EQ(opacity.interpolation, Interpolation::Constant);
    EXPECT_EQ(opacity.values, std::vector<float>{1.0f});
    EXPECT_EQ(diagnostics.warningCount(), 0u);
}
