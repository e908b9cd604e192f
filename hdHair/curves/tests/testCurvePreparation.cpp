#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/curves/BasisConversion.h"
#include "hdHair/curves/CatmullRomEvaluation.h"
#include "hdHair/curves/CurveTopology.h"
#include "hdHair/curves/PreparedCurves.h"
#include "hdHair/curves/ReferenceCurveEvaluator.h"
#include "hdHair/curves/tests/RandomCurves.h"
#include "hdHair/scene/tests/AuthoredPrimvar.h"

using namespace hdhair;

namespace {

using test::authoredPrimvar;
using test::randomPrim;

std::vector<float> randomValues(size_t count, float lo, float hi, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> value(lo, hi);
    std::vector<float> values(count);
    for (float& v : values) v = value(rng);
    return values;
}

const StrandControlPoint* segment(const PreparedCurves& prepared, size_t s) { return prepared.spanControls(s); }

bool containsMessage(const Diagnostics& diagnostics, const std::string& where, const std::string& message) {
    for (const Diagnostic& d : diagnostics.warnings())
        if (d.where == where && d.message == message) return true;
    return false;
}

}  // namespace

// Every span has four controls; Catmull-Rom curves' spans share theirs with
// their neighbours (a curve stores segments + 3), the other bases' do not.
TEST(PrepareCurves, ControlPointsPerSegment) {
    struct Case {
        CurveType type;
        CurveBasis basis;
        CurveWrap wrap;
        std::vector<int> counts;
        size_t segments;
        size_t controls;
    };
    const Case cases[] = {
        {CurveType::Cubic, CurveBasis::Bezier, CurveWrap::Nonperiodic, {4, 7, 10}, 1 + 2 + 3, 4 * 6},
        {CurveType::Cubic, CurveBasis::Bezier, CurveWrap::Periodic, {3, 6}, 1 + 2, 4 * 3},
        {CurveType::Cubic, CurveBasis::Bspline, CurveWrap::Nonperiodic, {4, 6}, 1 + 3, 4 * 4},
        {CurveType::Cubic, CurveBasis::Bspline, CurveWrap::Pinned, {2, 6}, 1 + 5, 4 * 6},
        {CurveType::Cubic, CurveBasis::CatmullRom, CurveWrap::Periodic, {5}, 5, 5 + 3},
        {CurveType::Cubic, CurveBasis::CatmullRom, CurveWrap::Pinned, {2, 6}, 1 + 5, (1 + 3) + (5 + 3)},
        {CurveType::Cubic, CurveBasis::CatmullRom, CurveWrap::Nonperiodic, {4, 9}, 1 + 6, 4 + 9},
        {CurveType::Linear, CurveBasis::Bezier, CurveWrap::Nonperiodic, {2, 5}, 1 + 4, 4 * 5},
        {CurveType::Linear, CurveBasis::Bezier, CurveWrap::Periodic, {3, 4}, 3 + 4, 4 * 7},
    };
    for (const Case& c : cases) {
        const CurvesPrim prim = randomPrim(c.type, c.basis, c.wrap, c.counts, 1);
        Diagnostics diagnostics;
        const PreparedCurves prepared = prepareCurves(prim, diagnostics);
        SCOPED_TRACE(toString(CurveKind{c.type, c.basis, c.wrap}));
        EXPECT_EQ(diagnostics.warningCount(), 0u);
        EXPECT_EQ(prepared.path, "/World/hair");
        EXPECT_EQ(prepared.segmentCount(), c.segments);
        EXPECT_EQ(prepared.controlPoints.size(), c.controls);
        ASSERT_EQ(prepared.segmentFirstControl.size(), c.segments);
        for (size_t s = 0; s < c.segments; ++s) EXPECT_LE(prepared.segmentFirstControl[s] + 4, c.controls);
        EXPECT_EQ(prepared.curveCount, c.counts.size());
        // Segments are in curve order, each naming its curve.
        const CurveTopology topology(prim);
        for (size_t curve = 0; curve < c.counts.size(); ++curve)
            for (size_t s = topology.segmentOffsets[curve]; s < topology.segmentOffsets[curve + 1]; ++s)
                EXPECT_EQ(prepared.segmentCurve[s], curve);
    }
}

// A shared span's four controls are exactly the ones the span would have
// alone (its stencil's), for positions and for every kind of primvar that
// allows sharing; a varying primvar (linear per span) stops the sharing.
TEST(PrepareCurves, SharedSpansHoldTheirOwnControls) {
    CurvesPrim prim = randomPrim(CurveType::Cubic, CurveBasis::CatmullRom, CurveWrap::Pinned, {3, 6}, 5);
    std::vector<float> widths;
    for (size_t v = 0; v < prim.points.size(); ++v) widths.push_back(0.01f * float(v + 1));
    prim.primvars["widths"] = authoredPrimvar("widths", Interpolation::Vertex, 1, widths);
    prim.primvars["displayOpacity"] = authoredPrimvar("displayOpacity", Interpolation::Uniform, 1, {0.25f, 0.75f});
    Diagnostics diagnostics;
    const PreparedCurves shared = prepareCurves(prim, diagnostics);
    ASSERT_EQ(shared.segmentCount(), 2u + 5u);
    EXPECT_EQ(shared.controlPoints.size(), (2u + 3u) + (5u + 3u));
    const CurveTopology topology(prim);
    for (size_t curve = 0; curve < 2; ++curve) {
        const int n = topology.vertexCount(curve);
        const size_t first = topology.vertexOffsets[curve];
        for (int s = 0; s < topology.segmentCount(curve); ++s) {
            const SpanStencil stencil = catmullRomStencil(topology.kind, n, s);
            float positions[12], spanWidths[4];
            applyStencil(stencil, &prim.points[first].x, 3, positions);
            applyStencil(stencil, &widths[first], 1, spanWidths);
            const StrandControlPoint* controls = shared.spanControls(topology.segmentOffsets[curve] + size_t(s));
            for (int r = 0; r < 4; ++r) {
                EXPECT_EQ(controls[r].position, glm::vec3(positions[3 * r], positions[3 * r + 1], positions[3 * r + 2]))
                    << curve << " " << s << " " << r;
                EXPECT_EQ(controls[r].width, spanWidths[r]);
                EXPECT_EQ(controls[r].opacity, curve == 0 ? 0.25f : 0.75f);
            }
        }
    }
    // Varying widths: linear per span, so each span keeps four of its own.
    prim.primvars["widths"] = authoredPrimvar("widths", Interpolation::Varying, 1, widths);
    const PreparedCurves unshared = prepareCurves(prim, diagnostics);
    EXPECT_EQ(unshared.controlPoints.size(), 4u * 7u);
    for (size_t s = 0; s < 7; ++s) {
        EXPECT_EQ(unshared.segmentFirstControl[s], 4u * s);
        for (int r = 0; r < 4; ++r) EXPECT_EQ(unshared.spanControls(s)[r].position, shared.spanControls(s)[r].position);
    }
    EXPECT_EQ(diagnostics.warningCount(), 0u);
}

TEST(PrepareCurves, ANonFinitePointDropsItsCurve) {
    CurvesPrim prim = randomPrim(CurveType::Cubic, CurveBasis::CatmullRom, CurveWrap::Nonperiodic, {4, 5, 6}, 2);
    prim.points[6].y = std::numeric_limits<float>::quiet_NaN();  // curve 1, its 3rd point
    prim.primvars["widths"] = authoredPrimvar("widths", Interpolation::Uniform, 1, {0.1f, 0.2f, 0.3f});
    Diagnostics diagnostics;
    const PreparedCurves prepared = prepareCurves(prim, diagnostics);
    EXPECT_EQ(prepared.curveCount, 2u);
    EXPECT_EQ(prepared.segmentCurve, (std::vector<uint32_t>{0, 2, 2, 2}));
    // Uniform data still follows the authored curve index.
    EXPECT_FLOAT_EQ(segment(prepared, 1)[1].width, 0.3f);
    ASSERT_EQ(diagnostics.warningCount(), 1u);
    EXPECT_EQ(diagnostics.warnings()[0].where, "/World/hair.points");
    EXPECT_EQ(diagnostics.warnings()[0].message, "curve 1 has a non-finite point (points[6]); dropping the curve");
    for (const StrandControlPoint& control : prepared.controlPoints)
        EXPECT_TRUE(std::isfinite(control.position.x) && std::isfinite(control.position.y));
}

TEST(PrepareCurves, InvisibleCurvesAreSkippedWithoutShiftingTheOthers) {
    CurvesPrim prim = randomPrim(CurveType::Cubic, CurveBasis::CatmullRom, CurveWrap::Nonperiodic, {4, 5, 6}, 2);
    prim.primvars["widths"] = authoredPrimvar("widths", Interpolation::Uniform, 1, {0.1f, 0.2f, 0.3f});
    // A hidden curve with a broken point: hidden, so not worth a warning.
    prim.points[6].y = std::numeric_limits<float>::quiet_NaN();
    prim.invisibleCurves = {1, 7, -1};  // out-of-range indices hide nothing
    Diagnostics diagnostics;
    const PreparedCurves prepared = prepareCurves(prim, diagnostics);
    EXPECT_EQ(prepared.curveCount, 2u);
    EXPECT_EQ(prepared.segmentCurve, (std::vector<uint32_t>{0, 2, 2, 2}));
    EXPECT_FLOAT_EQ(segment(prepared, 0)[1].width, 0.1f);
    EXPECT_FLOAT_EQ(segment(prepared, 1)[1].width, 0.3f);
    EXPECT_EQ(diagnostics.warningCount(), 0u);

    prim.invisibleCurves = {0, 1, 2};
    EXPECT_TRUE(prepareCurves(prim, diagnostics).empty());
}

TEST(PrepareCurves, ManyBadCurvesAreSummarised) {
    CurvesPrim prim =
        randomPrim(CurveType::Linear, CurveBasis::Bezier, CurveWrap::Nonperiodic, std::vector<int>(30, 2), 3);
    for (size_t i = 0; i < 25; ++i) prim.points[2 * i].x = std::numeric_limits<float>::infinity();
    Diagnostics diagnostics;
    const PreparedCurves prepared = prepareCurves(prim, diagnostics);
    EXPECT_EQ(prepared.curveCount, 5u);
    ASSERT_EQ(diagnostics.warningCount(), 11u);
    EXPECT_EQ(diagnostics.warnings()[10].message, "... and 15 more curves like that");
}

TEST(PrepareCurves, WidthsScaleWithTheTransform) {
    CurvesPrim prim = randomPrim(CurveType::Cubic, CurveBasis::Bezier, CurveWrap::Nonperiodic, {4}, 4);
    prim.primvars["widths"] = authoredPrimvar("widths", Interpolation::Constant, 1, {0.1f});
    Diagnostics diagnostics;
    const PreparedCurves unscaled = prepareCurves(prim, diagnostics);

    prim.worldTransform = glm::scale(glm::translate(glm::dmat4(1.0), glm::dvec3(5.0, -2.0, 1.0)), glm::dvec3(3.0));
    const PreparedCurves scaled = prepareCurves(prim, diagnostics);
    ASSERT_EQ(scaled.controlPoints.size(), 4u);
    for (size_t r = 0; r < 4; ++r) {
        EXPECT_NEAR(scaled.controlPoints[r].width, 0.3f, 1e-6f);
        const glm::vec3 expected = unscaled.controlPoints[r].position * 3.0f + glm::vec3(5.0f, -2.0f, 1.0f);
        EXPECT_NEAR(scaled.controlPoints[r].position.x, expected.x, 1e-5f);
        EXPECT_NEAR(scaled.controlPoints[r].position.y, expected.y, 1e-5f);
        EXPECT_NEAR(scaled.controlPoints[r].position.z, expected.z, 1e-5f);
    }
    // Non-uniform scale: the mean scale factor cbrt(|det|) = cbrt(1 * 8 * 1) = 2,
    // and a mirroring transform scales widths by the magnitude.
    prim.worldTransform = glm::scale(glm::dmat4(1.0), glm::dvec3(1.0, -8.0, 1.0));
    const PreparedCurves stretched = prepareCurves(prim, diagnostics);
    EXPECT_NEAR(stretched.controlPoints[0].width, 0.2f, 1e-6f);
    EXPECT_EQ(diagnostics.warningCount(), 0u);
}

TEST(PrepareCurves, BoundsContainEveryCurveAndItsWidth) {
    for (CurveBasis basis : {CurveBasis::Bezier, CurveBasis::Bspline, CurveBasis::CatmullRom}) {
        CurvesPrim prim = randomPrim(CurveType::Cubic, basis, CurveWrap::Nonperiodic, {7, 10, 13}, 5);
        prim.primvars["widths"] =
            authoredPrimvar("widths", Interpolation::Vertex, 1, randomValues(prim.points.size(), 0.0f, 0.3f, 6));
        prim.worldTransform = glm::rotate(glm::dmat4(1.0), 0.7, glm::dvec3(1.0, 1.0, 0.0));
        Diagnostics diagnostics;
        const PreparedCurves prepared = prepareCurves(prim, diagnostics);
        ASSERT_FALSE(prepared.empty());
        glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
        for (size_t s = 0; s < prepared.segmentCount(); ++s) {
            for (int i = 0; i <= 32; ++i) {
                const StrandControlPoint p = evaluate(segment(prepared, s), static_cast<float>(i) / 32.0f);
                const float radius = std::max(p.width, 0.0f) * 0.5f;
                for (int axis = 0; axis < 3; ++axis) {
                    EXPECT_LE(prepared.boundsMin[axis], p.position[axis] - radius + 1e-5f);
                    EXPECT_GE(prepared.boundsMax[axis], p.position[axis] + radius - 1e-5f);
                }
                lo = glm::min(lo, p.position - radius);
                hi = glm::max(hi, p.position + radius);
            }
        }
        // Conservative, but not wildly so.
        const glm::vec3 extent = hi - lo;
        for (int axis = 0; axis < 3; ++axis) {
            EXPECT_LT(lo[axis] - prepared.boundsMin[axis], 0.5f * extent[axis]) << toString(basis);
            EXPECT_LT(prepared.boundsMax[axis] - hi[axis], 0.5f * extent[axis]) << toString(basis);
        }
    }
}

TEST(PrepareCurves, EmptyPrimHasEmptyBounds) {
    CurvesPrim prim;
    prim.path = "/World/empty";
    Diagnostics diagnostics;
    const PreparedCurves prepared = prepareCurves(prim, diagnostics);
    EXPECT_TRUE(prepared.empty());
    EXPECT_EQ(prepared.curveCount, 0u);
    EXPECT_GT(prepared.boundsMin.x, prepared.boundsMax.x);
    EXPECT_EQ(diagnostics.warningCount(), 0u);
}

// Vertex widths and colours go through the same change of basis as the points:
// the prepared curve carries the authored attribute curves exactly.
TEST(PrepareCurves, VertexPrimvarsMatchTheReferenceEvaluator) {
    for (CurveBasis basis : {CurveBasis::Bezier, CurveBasis::Bspline, CurveBasis::CatmullRom}) {
        for (CurveWrap wrap : {CurveWrap::Nonperiodic, CurveWrap::Periodic, CurveWrap::Pinned}) {
            const std::vector<int> counts =
                basis == CurveBasis::Bezier ? std::vector<int>{7, 6} : std::vector<int>{5, 6};
            CurvesPrim prim = randomPrim(CurveType::Cubic, basis, wrap, counts, 8);
            const size_t n = prim.points.size();
            prim.primvars["widths"] = authoredPrimvar("widths", Interpolation::Vertex, 1, randomValues(n, 0.1f, 0.5f, 9));
            prim.primvars["displayColor"] =
                authoredPrimvar("displayColor", Interpolation::Vertex, 3, randomValues(3 * n, 0.0f, 1.0f, 10));
            prim.worldTransform = glm::scale(glm::dmat4(1.0), glm::dvec3(2.0));
            Diagnostics diagnostics;
            const PreparedCurves prepared = prepareCurves(prim, diagnostics);
            const ReferenceCurveEvaluator reference(prim);
            const CurveTopology& topology = reference.topology();
            ASSERT_EQ(prepared.segmentCount(), topology.segmentTotal());
            for (size_t curve = 0; curve < topology.curveCount(); ++curve) {
                for (int s = 0; s < topology.segmentCount(curve); ++s) {
                    const StrandControlPoint* controls =
                        segment(prepared, topology.segmentOffsets[curve] + static_cast<size_t>(s));
                    for (int i = 0; i <= 8; ++i) {
                        const double u = i / 8.0;
                        const StrandControlPoint p = evaluate(controls, static_cast<float>(u));
                        double width = 0.0;
                        glm::dvec3 color;
                        reference.evaluate(prim.primvars["widths"].values.data(), 1, curve, s, u, &width);
                        reference.evaluate(prim.primvars["displayColor"].values.data(), 3, curve, s, u,
                                           glm::value_ptr(color));
                        const glm::dvec3 position = 2.0 * reference.position(curve, s, u);
                        SCOPED_TRACE(toString(topology.kind) + " curve " + std::to_string(curve) + " span " +
                                     std::to_string(s));
                        EXPECT_NEAR(p.width, 2.0 * width, 1e-5);
                        for (int c = 0; c < 3; ++c) {
                            EXPECT_NEAR(p.color[c], color[c], 1e-5);
                            EXPECT_NEAR(p.position[c], position[c], 1e-5);
                        }
                        EXPECT_FLOAT_EQ(p.opacity, 1.0f);
                    }
                }
            }
        }
    }
}

TEST(PrepareCurves, VaryingPrimvarsInterpolateLinearlyBetweenSpanEnds) {
    // Bezier, 3 spans: 4 varying values, one per span end.
    CurvesPrim prim = randomPrim(CurveType::Cubic, CurveBasis::Bezier, CurveWrap::Nonperiodic, {10}, 11);
    prim.primvars["widths"] = authoredPrimvar("widths", Interpolation::Varying, 1, {0.1f, 0.4f, 0.2f, 0.3f});
    prim.primvars["displayOpacity"] =
        authoredPrimvar("displayOpacity", Interpolation::Varying, 1, {1.0f, 0.0f, 0.5f, 1.0f});
    Diagnostics diagnostics;
    const PreparedCurves prepared = prepareCurves(prim, diagnostics);
    EXPECT_EQ(diagnostics.warningCount(), 0u);
    ASSERT_EQ(prepared.segmentCount(), 3u);
    const float widths[] = {0.1f, 0.4f, 0.2f, 0.3f}, opacities[] = {1.0f, 0.0f, 0.5f, 1.0f};
    for (size_t s = 0; s < 3; ++s) {
        for (int i = 0; i <= 10; ++i) {
            const float u = static_cast<float>(i) / 10.0f;
            const StrandControlPoint p = evaluate(segment(prepared, s), u);
            EXPECT_NEAR(p.width, widths[s] + u * (widths[s + 1] - widths[s]), 1e-6f);
            EXPECT_NEAR(p.opacity, opacities[s] + u * (opacities[s + 1] - opacities[s]), 1e-6f);
        }
    }
}

TEST(PrepareCurves, PeriodicVaryingWrapsAndPinnedVaryingHoldsAtTheEnds) {
    CurvesPrim periodic = randomPrim(CurveType::Cubic, CurveBasis::Bspline, CurveWrap::Periodic, {4}, 12);
    periodic.primvars["displayColor"] =
        authoredPrimvar("displayColor", Interpolation::Varying, 3, {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1});
    Diagnostics diagnostics;
    const PreparedCurves closed = prepareCurves(periodic, diagnostics);
    ASSERT_EQ(closed.segmentCount(), 4u);
    const StrandControlPoint seam = evaluate(segment(closed, 3), 0.5f);  // from value 3 back to value 0
    EXPECT_NEAR(seam.color.z, 0.5f, 1e-6f);
    EXPECT_NEAR(seam.color.x, 0.0f, 1e-6f);

    // Pinned catmullRom, n = 5: 4 spans; 3 varying values (nonperiodic size).
    CurvesPrim pinned = randomPrim(CurveType::Cubic, CurveBasis::CatmullRom, CurveWrap::Pinned, {5}, 13);
    pinned.primvars["widths"] = authoredPrimvar("widths", Interpolation::Varying, 1, {0.1f, 0.2f, 0.3f});
    const PreparedCurves open = prepareCurves(pinned, diagnostics);
    ASSERT_EQ(open.segmentCount(), 4u);
    EXPECT_NEAR(evaluate(segment(open, 0), 0.5f).width, 0.1f, 1e-6f);
    EXPECT_NEAR(evaluate(segment(open, 1), 0.5f).width, 0.15f, 1e-6f);
    EXPECT_NEAR(evaluate(segment(open, 3), 0.5f).width, 0.3f, 1e-6f);
    EXPECT_EQ(diagnostics.warningCount(), 0u);
}

TEST(PrepareCurves, UniformAndConstantPrimvarsAreHeldAlongTheSpan) {
    CurvesPrim prim = randomPrim(CurveType::Cubic, CurveBasis::Bspline, CurveWrap::Nonperiodic, {4, 5}, 14);
    prim.primvars["displayColor"] = authoredPrimvar("displayColor", Interpolation::Uniform, 3, {1, 0, 0, 0, 0, 1});
    prim.primvars["displayOpacity"] = authoredPrimvar("displayOpacity", Interpolation::Constant, 1, {0.25f});
    prim.primvars["opacity"] = authoredPrimvar("opacity", Interpolation::Constant, 1, {0.0f});  // not displayOpacity
    Diagnostics diagnostics;
    const PreparedCurves prepared = prepareCurves(prim, diagnostics);
    ASSERT_EQ(prepared.segmentCount(), 3u);
    for (size_t s = 0; s < 3; ++s) {
        const glm::vec3 expected = s == 0 ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1);
        for (int r = 0; r < 4; ++r) {
            EXPECT_EQ(segment(prepared, s)[r].color, expected);
            EXPECT_EQ(segment(prepared, s)[r].opacity, 0.25f);
            EXPECT_EQ(segment(prepared, s)[r].width, 1.0f);  // unauthored: Hydra's fallback
        }
    }
    EXPECT_EQ(segment(prepared, 0)[0].color, glm::vec3(1, 0, 0));
    EXPECT_EQ(diagnostics.warningCount(), 0u);
}

TEST(PrepareCurves, UnauthoredColourIsGrey) {
    const CurvesPrim prim = randomPrim(CurveType::Linear, CurveBasis::Bezier, CurveWrap::Nonperiodic, {2}, 15);
    Diagnostics diagnostics;
    const PreparedCurves prepared = prepareCurves(prim, diagnostics);
    ASSERT_EQ(prepared.controlPoints.size(), 4u);
    EXPECT_EQ(prepared.controlPoints[0].color, glm::vec3(0.5f));
    EXPECT_EQ(prepared.controlPoints[0].opacity, 1.0f);
}

TEST(PrepareCurves, NegativeWidthsAreClampedToZero) {
    CurvesPrim prim = randomPrim(CurveType::Linear, CurveBasis::Bezier, CurveWrap::Nonperiodic, {3}, 16);
    prim.primvars["widths"] = authoredPrimvar("widths", Interpolation::Vertex, 1, {0.2f, -0.1f, -0.3f});
    Diagnostics diagnostics;
    const PreparedCurves prepared = prepareCurves(prim, diagnostics);
    EXPECT_NEAR(evaluate(segment(prepared, 0), 0.0f).width, 0.2f, 1e-6f);
    EXPECT_NEAR(evaluate(segment(prepared, 0), 1.0f).width, 0.0f, 1e-6f);
    EXPECT_NEAR(evaluate(segment(prepared, 1), 1.0f).width, 0.0f, 1e-6f);
    ASSERT_EQ(diagnostics.warningCount(), 1u);
    EXPECT_EQ(diagnostics.warnings()[0].where, "/World/hair.widths");
    EXPECT_EQ(diagnostics.warnings()[0].message, "2 negative widths; clamped to 0");
}

TEST(PrepareCurves, StormPrimvarsHdHairDoesNotHonourAreReported) {
    // OpenUSD's moreCurves.usda and curvesWithScreenSpaceWidths.usda author
    // these; Storm changes what it draws for each, hdHair does not.
    CurvesPrim prim = randomPrim(CurveType::Linear, CurveBasis::Bezier, CurveWrap::Nonperiodic, {3}, 18);
    prim.primvars["normals"] = authoredPrimvar("normals", Interpolation::Varying, 3, std::vector<float>(9, 1.0f));
    prim.primvars["screenSpaceWidths"] = authoredPrimvar("screenSpaceWidths", Interpolation::Constant, 1, {1.0f});
    prim.primvars["minScreenSpaceWidths"] = authoredPrimvar("minScreenSpaceWidths", Interpolation::Constant, 1, {10.0f});
    Diagnostics diagnostics;
    prepareCurves(prim, diagnostics);
    ASSERT_EQ(diagnostics.warningCount(), 3u);
    EXPECT_TRUE(containsMessage(diagnostics, "/World/hair.normals",
                                "not used: hdHair draws camera-facing strands, not ribbons oriented by normals"));
    EXPECT_TRUE(containsMessage(diagnostics, "/World/hair.primvars:screenSpaceWidths",
                                "not supported: widths are drawn as object-space diameters, not pixels"));
    EXPECT_TRUE(containsMessage(diagnostics, "/World/hair.primvars:minScreenSpaceWidths",
                                "not supported: strands thinner than the minPixelWidth setting (default 1 pixel) are "
                                "drawn that wide, with their coverage as alpha"));

    // Authored as off, the screen-space primvars change nothing in Storm either.
    prim.primvars.erase("normals");
    prim.primvars["screenSpaceWidths"].values = {0.0f};
    prim.primvars["minScreenSpaceWidths"].values = {0.0f};
    Diagnostics off;
    prepareCurves(prim, off);
    EXPECT_EQ(off.warningCount(), 0u);
}

TEST(PrepareCurves, UnderLengthCurvesAreDrawnAsStormDoes) {
    // bunnyCurves.usda's bezier counts 8, 9 and 5; and a 1-vertex curve.
    CurvesPrim prim = randomPrim(CurveType::Cubic, CurveBasis::Bezier, CurveWrap::Nonperiodic, {8, 9, 5, 1, 4}, 17);
    Diagnostics diagnostics;
    const PreparedCurves prepared = prepareCurves(prim, diagnostics);
    EXPECT_EQ(prepared.segmentCount(), 2u + 2u + 1u + 1u);
    EXPECT_EQ(prepared.curveCount, 4u);
    EXPECT_EQ(diagnostics.warningCount(), 4u);
    const std::string where = "/World/hair.curveVertexCounts";
    EXPECT_TRUE(containsMessage(diagnostics, where,
                                "curve 0 has 8 vertices, but cubic bezier nonperiodic curves need 4 + 3k vertices "
                                "(k >= 0); drawing it as Storm does (repeating its last vertex)"));
    EXPECT_TRUE(containsMessage(diagnostics, where,
                                "curve 3 has 1 vertices, too few for a single cubic bezier nonperiodic span; "
                                "skipping it"));
    // Curve 2 (n = 5): one span on vertices 0..3, the 5th vertex unused.
    const ReferenceCurveEvaluator reference(prim);
    const StrandControlPoint* controls = segment(prepared, 4);
    for (int i = 0; i <= 4; ++i) {
        const glm::dvec3 expected = reference.position(2, 0, i / 4.0);
        const glm::vec3 actual = evaluate(controls, static_cast<float>(i) / 4.0f).position;
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(actual[c], expected[c], 1e-5);
    }
}

TEST(PrepareCurves, CountsThatDoNotMatchThePointsKeepOnlyCompleteCurves) {
    CurvesPrim prim = randomPrim(CurveType::Cubic, CurveBasis::CatmullRom, CurveWrap::Nonperiodic, {4, 6}, 18);
    prim.points.resize(8);  // the second curve lacks 2 vertices
    Diagnostics diagnostics;
    const PreparedCurves missing = prepareCurves(prim, diagnostics);
    EXPECT_EQ(missing.curveCount, 1u);
    EXPECT_EQ(missing.segmentCurve, std::vector<uint32_t>{0});
    EXPECT_TRUE(containsMessage(diagnostics, "/World/hair.points",
                                "curveVertexCounts add up to 10 vertices, but there are 8 points; dropping the curves "
                                "whose vertices are missing"));
    EXPECT_TRUE(containsMessage(diagnostics, "/World/hair.points",
                                "curve 1 needs points [4, 10), past the last point; dropping the curve"));

    prim.points.resize(12, glm::vec3(0.0f));
    Diagnostics more;
    const PreparedCurves extra = prepareCurves(prim, more);
    EXPECT_EQ(extra.curveCount, 2u);
    ASSERT_EQ(more.warningCount(), 1u);
    EXPECT_EQ(more.warnings()[0].message,
              "curveVertexCounts add up to 10 vertices, but there are 12 points; ignoring the extra points");
}

TEST(PrepareCurves, WrongPrimvarsAreReportedAndReplaced) {
    CurvesPrim prim = randomPrim(CurveType::Cubic, CurveBasis::Bezier, CurveWrap::Nonperiodic, {4, 4, 4}, 19);
    prim.primvars["displayColor"] = authoredPrimvar("displayColor", Interpolation::Vertex, 3, std::vector<float>(21, 1.0f));
    Diagnostics diagnostics;
    const PreparedCurves prepared = prepareCurves(prim, diagnostics);
    EXPECT_EQ(prepared.segmentCount(), 3u);
    for (const StrandControlPoint& control : prepared.controlPoints) EXPECT_EQ(control.color, glm::vec3(0.5f));
    ASSERT_EQ(diagnostics.warningCount(), 1u);
    EXPECT_EQ(diagnostics.warnings()[0].where + ": " + diagnostics.warnings()[0].message,
              "/World/hair.primvars:displayColor: vertex interpolation needs 12 values, found 7; using the fallback "
              "(0.5, 0.5, 0.5)");
}

// Many curves (parallel path) and many prims at once (Hydra syncs in
// parallel): the result does not depend on the scheduling.
TEST(PrepareCurves, ParallelPreparationIsDeterministic) {
    std::vector<int> counts(5000);
    for (size_t i = 0; i < counts.size(); ++i) counts[i] = 4 + static_cast<int>(i % 7);
    std::vector<CurvesPrim> prims;
    for (unsigned p = 0; p < 4; ++p) {
        prims.push_back(randomPrim(CurveType::Cubic, CurveBasis::Bspline, CurveWrap::Pinned, counts, 20 + p));
        prims.back().points[3 * p + 1].x = std::numeric_limits<float>::quiet_NaN();
    }
    std::vector<PreparedCurves> parallel(prims.size());
    Diagnostics shared;
    std::vector<std::thread> threads;
    for (size_t p = 0; p < prims.size(); ++p)
        threads.emplace_back([&, p] { parallel[p] = prepareCurves(prims[p], shared); });
    for (std::thread& thread : threads) thread.join();
    EXPECT_EQ(shared.warningCount(), prims.size());

    for (size_t p = 0; p < prims.size(); ++p) {
        Diagnostics diagnostics;
        const PreparedCurves serial = prepareCurves(prims[p], diagnostics);
        ASSERT_EQ(serial.segmentCount(), parallel[p].segmentCount());
        EXPECT_EQ(serial.curveCount, counts.size() - 1);
        EXPECT_EQ(serial.segmentCurve, parallel[p].segmentCurve);
        EXPECT_TRUE(std::is_sorted(serial.segmentCurve.begin(), serial.segmentCurve.end()));
        EXPECT_EQ(serial.boundsMin, parallel[p].boundsMin);
        EXPECT_EQ(serial.boundsMax, parallel[p].boundsMax);
        EXPECT_EQ(0, std::memcmp(serial.controlPoints.data(), parallel[p].controlPoints.data(),
                                 serial.controlPoints.size() * sizeof(StrandControlPoint)));
    }
}

TEST(CurvePreparation, OpacityComesFromPrimvarsOpacityWhenDisplayOpacityIsAbsent) {
    CurvesPrim prim;
    prim.path = "/hair";
    prim.type = CurveType::Linear;
    prim.curveVertexCounts = {2};
    prim.points = {{0, 0, 0}, {1, 0, 0}};
    Primvar opacity;
    opacity.name = "opacity";
    opacity.values = {0.25f};
    prim.primvars["opacity"] = opacity;
    Diagnostics diagnostics;
    EXPECT_FLOAT_EQ(prepareCurves(prim, diagnostics).controlPoints[1].opacity, 0.25f);
    // displayOpacity, when authored, wins.
    opacity.name = "displayOpacity";
    opacity.values = {0.75f};
    prim.primvars["displayOpacity"] = opacity;
    EXPECT_FLOAT_EQ(prepareCurves(prim, diagnostics).controlPoints[1].opacity, 0.75f);
    EXPECT_TRUE(diagnostics.warnings().empty());
}

TEST(CurvePreparation, RequestedShadingPrimvarsTravelWithTheControlPointsLikeColours) {
    const std::vector<ShadingPrimvarRequest> requests{{"hdHair:tint", {0.0f, 0.0f, 0.0f}},
                                                      {"hdHair:unauthored", {1.0f}},
                                                      {"hdHair:constant", {1.0f}}};
    for (CurveBasis basis : {CurveBasis::Bezier, CurveBasis::Bspline, CurveBasis::CatmullRom}) {
        for (CurveWrap wrap : {CurveWrap::Nonperiodic, CurveWrap::Periodic, CurveWrap::Pinned}) {
            if (basis == CurveBasis::Bezier && wrap == CurveWrap::Pinned) continue;
            std::vector<int> counts{7, 10};
            if (basis == CurveBasis::Bezier && wrap == CurveWrap::Periodic) counts = {6, 9};
            CurvesPrim prim = randomPrim(CurveType::Cubic, basis, wrap, counts, 11);
            const size_t vertices = prim.points.size();
            std::vector<float> tint = randomValues(3 * vertices, 0.0f, 1.0f, 5);
            prim.primvars["displayColor"] = authoredPrimvar("displayColor", Interpolation::Vertex, 3, tint);
            prim.primvars["hdHair:tint"] = authoredPrimvar("hdHair:tint", Interpolation::Vertex, 3, tint);
            prim.primvars["hdHair:constant"] = authoredPrimvar("hdHair:constant", Interpolation::Uniform, 1, {2.0f, 2.0f});
            Diagnostics diagnostics;
            const PreparedCurves prepared = prepareCurves(prim, diagnostics, requests);
            ASSERT_EQ(prepared.shadingPrimvars.size(), 2u) << "only authored primvars are carried";
            EXPECT_EQ(prepared.findShadingPrimvar("hdHair:unauthored"), nullptr);
            const PreparedShadingPrimvar* constant = prepared.findShadingPrimvar("hdHair:constant");
            ASSERT_NE(constant, nullptr);
            EXPECT_FALSE(constant->varying) << "equal per-curve values are one value";
            EXPECT_EQ(constant->values, std::vector<float>{2.0f});
            const PreparedShadingPrimvar* carried = prepared.findShadingPrimvar("hdHair:tint");
            ASSERT_NE(carried, nullptr);
            ASSERT_TRUE(carried->varying);
            ASSERT_EQ(carried->values.size(), 3 * prepared.controlPoints.size());
            for (size_t k = 0; k < prepared.controlPoints.size(); ++k)
                EXPECT_EQ(glm::make_vec3(carried->at(k)), prepared.controlPoints[k].color) << k;
            EXPECT_TRUE(diagnostics.warnings().empty());
        }
    }
}

// Found by fuzzCurvePreparation (hdHair/fuzz/regressions): a hair primvar on
// a prim whose curves all vanish resolves to no elements, and preparing it
// read past an empty array.
TEST(CurvePreparation, AHairPrimvarOnAPrimOfNoCurvesCarriesNothing) {
    CurvesPrim prim;
    prim.path = "/none";
    prim.type = CurveType::Linear;
    Primvar melanin;
    melanin.name = "hdHair:melanin";
    melanin.interpolation = Interpolation::Uniform;
    melanin.interpolationAuthored = true;
    prim.primvars["hdHair:melanin"] = melanin;
    Diagnostics diagnostics;
    PreparedCurves prepared = prepareCurves(prim, diagnostics, {{"hdHair:melanin", {0.3f}, 0.0f, 1.0f}});
    EXPECT_TRUE(prepared.empty());
    EXPECT_TRUE(prepared.shadingPrimvars.empty());
}
