// The change of basis (BasisConversion) against the reference evaluator, which
// evaluates every basis directly, and the shape properties each wrap promises.

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "hdHair/curves/BasisConversion.h"
#include "hdHair/curves/CatmullRomEvaluation.h"
#include "hdHair/curves/CurveTopology.h"
#include "hdHair/curves/ReferenceCurveEvaluator.h"
#include "hdHair/curves/tests/RandomCurves.h"

using namespace hdhair;

namespace {

constexpr double kTolerance = 1e-5;

using test::randomPrim;

// The span's Catmull-Rom controls, as the prepared curves hold them (positions only).
std::array<StrandControlPoint, 4> convertedSpan(const CurvesPrim& prim, const CurveTopology& topology, size_t curve,
                                                int span) {
    float positions[12];
    const SpanStencil stencil = catmullRomStencil(topology.kind, topology.vertexCount(curve), span);
    applyStencil(stencil, glm::value_ptr(prim.points[topology.vertexOffsets[curve]]), 3, positions);
    std::array<StrandControlPoint, 4> controls{};
    for (int r = 0; r < 4; ++r)
        controls[static_cast<size_t>(r)].position =
            glm::vec3(positions[3 * r], positions[3 * r + 1], positions[3 * r + 2]);
    return controls;
}

void expectNear(const glm::dvec3& actual, const glm::dvec3& expected, double tolerance, const std::string& what) {
    EXPECT_NEAR(actual.x, expected.x, tolerance) << what;
    EXPECT_NEAR(actual.y, expected.y, tolerance) << what;
    EXPECT_NEAR(actual.z, expected.z, tolerance) << what;
}

std::vector<CurveKind> allKinds() {
    std::vector<CurveKind> kinds;
    for (CurveWrap wrap : {CurveWrap::Nonperiodic, CurveWrap::Periodic, CurveWrap::Pinned}) {
        for (CurveBasis basis : {CurveBasis::Bezier, CurveBasis::Bspline, CurveBasis::CatmullRom})
            kinds.push_back({CurveType::Cubic, basis, wrap});
        kinds.push_back({CurveType::Linear, CurveBasis::Bezier, wrap});
    }
    return kinds;
}

}  // namespace

TEST(CatmullRomEvaluation, WeightsArePartitionOfUnityAndInterpolateTheMiddleControls) {
    for (int i = 0; i <= 20; ++i) {
        const float u = static_cast<float>(i) / 20.0f;
        const std::array<float, 4> w = catmullRomWeights(u);
        const std::array<float, 4> d = catmullRomDerivativeWeights(u);
        EXPECT_NEAR(w[0] + w[1] + w[2] + w[3], 1.0f, 1e-6f);
        EXPECT_NEAR(d[0] + d[1] + d[2] + d[3], 0.0f, 1e-6f);
        // The derivative weights are the derivative of the weights.
        const float h = 1e-3f;
        const std::array<float, 4> ahead = catmullRomWeights(u + h), behind = catmullRomWeights(u - h);
        for (size_t k = 0; k < 4; ++k) EXPECT_NEAR(d[k], (ahead[k] - behind[k]) / (2.0f * h), 1e-3f);
    }
    EXPECT_EQ(catmullRomWeights(0.0f), (std::array<float, 4>{0.0f, 1.0f, 0.0f, 0.0f}));
    EXPECT_EQ(catmullRomWeights(1.0f), (std::array<float, 4>{0.0f, 0.0f, 1.0f, 0.0f}));
    // Tension 0.5: end tangents (C2-C0)/2 and (C3-C1)/2.
    EXPECT_EQ(catmullRomDerivativeWeights(0.0f), (std::array<float, 4>{-0.5f, 0.0f, 0.5f, 0.0f}));
    EXPECT_EQ(catmullRomDerivativeWeights(1.0f), (std::array<float, 4>{0.0f, -0.5f, 0.0f, 0.5f}));
}

TEST(CatmullRomEvaluation, EvaluateInterpolatesEveryAttribute) {
    StrandControlPoint controls[4];
    for (int i = 0; i < 4; ++i) {
        const float f = static_cast<float>(i);
        controls[i] = {glm::vec3(f, 2.0f * f, -f), 0.1f * f, glm::vec3(0.2f * f), 1.0f - 0.25f * f};
    }
    const StrandControlPoint start = evaluate(controls, 0.0f);
    const StrandControlPoint end = evaluate(controls, 1.0f);
    EXPECT_EQ(start.position, controls[1].position);
    EXPECT_EQ(end.position, controls[2].position);
    EXPECT_FLOAT_EQ(start.width, controls[1].width);
    EXPECT_FLOAT_EQ(end.opacity, controls[2].opacity);
    // Collinear, evenly spaced controls: CR is linear in u.
    const StrandControlPoint middle = evaluate(controls, 0.5f);
    EXPECT_NEAR(middle.position.y, 3.0f, 1e-6f);
    EXPECT_NEAR(middle.width, 0.15f, 1e-6f);
    EXPECT_NEAR(middle.color.x, 0.3f, 1e-6f);
    EXPECT_NEAR(middle.opacity, 0.625f, 1e-6f);
    expectNear(glm::dvec3(evaluateTangent(controls, 0.3f)), glm::dvec3(1.0, 2.0, -1.0), 1e-6, "tangent");
}

TEST(BasisConversion, MatrixRowsSumToOneSoConversionIsAffine) {
    for (CurveBasis basis : {CurveBasis::Bezier, CurveBasis::Bspline, CurveBasis::CatmullRom}) {
        for (const auto& row : catmullRomFromBasis(basis)) EXPECT_NEAR(row[0] + row[1] + row[2] + row[3], 1.0, 1e-12);
    }
}

TEST(BasisConversion, CatmullRomInterpolatesItsControlPoints) {
    const CurveKind kind{CurveType::Cubic, CurveBasis::CatmullRom, CurveWrap::Nonperiodic};
    const CurvesPrim prim = randomPrim(kind, {7}, 1);
    const CurveTopology topology(prim);
    ASSERT_EQ(topology.segmentCount(0), 4);
    for (int s = 0; s < 4; ++s) {
        const auto controls = convertedSpan(prim, topology, 0, s);
        // Identity conversion, and span s runs from P[s+1] to P[s+2].
        for (int r = 0; r < 4; ++r)
            EXPECT_EQ(controls[static_cast<size_t>(r)].position, prim.points[static_cast<size_t>(s + r)]);
        EXPECT_EQ(evaluate(controls.data(), 0.0f).position, prim.points[static_cast<size_t>(s + 1)]);
        EXPECT_EQ(evaluate(controls.data(), 1.0f).position, prim.points[static_cast<size_t>(s + 2)]);
    }
}

// Every basis and wrap, valid and under-length curves: the converted span is
// the authored curve, in position and in derivative.
TEST(BasisConversion, ConvertedSpansMatchTheReferenceEvaluator) {
    // Spans of curves of 2..10 and 13 vertices, by HdSt's rules (README's
    // table; counts 2 and 3 are under-length for the cubic nonperiodic
    // kinds and still drawn as one span): every one is compared below.
    const std::map<std::string, int> expectedSpans = {
        {"linear nonperiodic", 57}, {"linear periodic", 67}, {"linear pinned", 57},
        {"cubic bezier nonperiodic", 18}, {"cubic bezier periodic", 20}, {"cubic bezier pinned", 18},
        {"cubic bspline nonperiodic", 40}, {"cubic bspline periodic", 67}, {"cubic bspline pinned", 57},
        {"cubic catmullRom nonperiodic", 40}, {"cubic catmullRom periodic", 67}, {"cubic catmullRom pinned", 57},
    };
    unsigned seed = 10;
    for (const CurveKind& kind : allKinds()) {
        const CurvesPrim prim = randomPrim(kind, {2, 3, 4, 5, 6, 7, 8, 9, 10, 13}, seed++);
        const CurveTopology topology(prim);
        const ReferenceCurveEvaluator reference(prim);
        int spansChecked = 0;
        for (size_t curve = 0; curve < topology.curveCount(); ++curve) {
            for (int s = 0; s < topology.segmentCount(curve); ++s) {
                const auto controls = convertedSpan(prim, topology, curve, s);
                for (int i = 0; i <= 16; ++i) {
                    const float u = static_cast<float>(i) / 16.0f;
                    const std::string what = toString(kind) + " curve " + std::to_string(curve) + " span " +
                                             std::to_string(s) + " u " + std::to_string(u);
                    expectNear(glm::dvec3(evaluate(controls.data(), u).position), reference.position(curve, s, u),
                               kTolerance, what);
                    expectNear(glm::dvec3(evaluateTangent(controls.data(), u)), reference.derivative(curve, s, u),
                               10 * kTolerance, what + " (derivative)");
                }
                ++spansChecked;
            }
        }
        EXPECT_EQ(spansChecked, expectedSpans.at(toString(kind))) << toString(kind);
    }
}

// The change of basis must never name a vertex outside the curve, however
// short the curve is (HdSt clamps or wraps).
TEST(BasisConversion, StencilsStayInsideTheCurve) {
    for (const CurveKind& kind : allKinds()) {
        for (int n = 1; n <= 12; ++n) {
            for (int s = 0; s < segmentCount(kind, n); ++s) {
                const SpanStencil stencil = catmullRomStencil(kind, n, s);
                for (const SpanStencil::Control& control : stencil.controls) {
                    ASSERT_GT(control.termCount, 0);
                    double sum = 0.0;
                    for (int t = 0; t < control.termCount; ++t) {
                        EXPECT_GE(control.terms[static_cast<size_t>(t)].vertex, 0);
                        EXPECT_LT(control.terms[static_cast<size_t>(t)].vertex, n) << toString(kind) << " n " << n;
                        sum += control.terms[static_cast<size_t>(t)].weight;
                    }
                    EXPECT_NEAR(sum, 1.0, 1e-12);
                }
            }
        }
    }
}

TEST(BasisConversion, PeriodicCurvesAreC1AtTheSeam) {
    for (CurveBasis basis : {CurveBasis::Bezier, CurveBasis::Bspline, CurveBasis::CatmullRom}) {
        const CurveKind kind{CurveType::Cubic, basis, CurveWrap::Periodic};
        CurvesPrim prim = randomPrim(kind, {9}, 42);
        if (basis == CurveBasis::Bezier) {
            // Bezier joints are C1 only when authored so: mirror each joint's
            // incoming handle to make its outgoing one.
            for (size_t joint = 0; joint < 9; joint += 3) {
                const size_t in = (joint + 8) % 9, out = joint + 1;
                prim.points[out] = 2.0f * prim.points[joint] - prim.points[in];
            }
        }
        const CurveTopology topology(prim);
        const int spans = topology.segmentCount(0);
        ASSERT_EQ(spans, basis == CurveBasis::Bezier ? 3 : 9);
        // Every joint, the seam (last -> first span) included.
        for (int s = 0; s < spans; ++s) {
            const auto a = convertedSpan(prim, topology, 0, s);
            const auto b = convertedSpan(prim, topology, 0, (s + 1) % spans);
            const std::string what = std::string(toString(basis)) + " joint after span " + std::to_string(s);
            expectNear(glm::dvec3(evaluate(a.data(), 1.0f).position), glm::dvec3(evaluate(b.data(), 0.0f).position),
                       kTolerance, what);
            expectNear(glm::dvec3(evaluateTangent(a.data(), 1.0f)), glm::dvec3(evaluateTangent(b.data(), 0.0f)),
                       10 * kTolerance, what + " (derivative)");
        }
    }
}

TEST(BasisConversion, PinnedCurvesStartAndEndOnTheirEndPoints) {
    for (CurveBasis basis : {CurveBasis::Bspline, CurveBasis::CatmullRom}) {
        const CurveKind kind{CurveType::Cubic, basis, CurveWrap::Pinned};
        const CurvesPrim prim = randomPrim(kind, {2, 3, 4, 7}, 7);
        const CurveTopology topology(prim);
        for (size_t curve = 0; curve < topology.curveCount(); ++curve) {
            const int n = topology.vertexCount(curve);
            ASSERT_EQ(topology.segmentCount(curve), n - 1);
            const glm::vec3 first = prim.points[topology.vertexOffsets[curve]];
            const glm::vec3 last = prim.points[topology.vertexOffsets[curve + 1] - 1];
            const auto head = convertedSpan(prim, topology, curve, 0);
            const auto tail = convertedSpan(prim, topology, curve, n - 2);
            const std::string what = std::string(toString(basis)) + " n " + std::to_string(n);
            expectNear(glm::dvec3(evaluate(head.data(), 0.0f).position), glm::dvec3(first), 1e-6, what);
            expectNear(glm::dvec3(evaluate(tail.data(), 1.0f).position), glm::dvec3(last), 1e-6, what);
            // And the spans join up in between.
            for (int s = 0; s + 1 < n - 1; ++s) {
                const auto a = convertedSpan(prim, topology, curve, s);
                const auto b = convertedSpan(prim, topology, curve, s + 1);
                expectNear(glm::dvec3(evaluate(a.data(), 1.0f).position), glm::dvec3(evaluate(b.data(), 0.0f).position),
                           kTolerance, what);
            }
        }
    }
}

TEST(BasisConversion, PinnedBezierIsNonperiodicBezier) {
    const CurvesPrim pinned = randomPrim({CurveType::Cubic, CurveBasis::Bezier, CurveWrap::Pinned}, {7}, 3);
    CurvesPrim nonperiodic = pinned;
    nonperiodic.wrap = CurveWrap::Nonperiodic;
    const CurveTopology a(pinned), b(nonperiodic);
    ASSERT_EQ(a.segmentCount(0), 2);
    for (int s = 0; s < 2; ++s) {
        const auto x = convertedSpan(pinned, a, 0, s), y = convertedSpan(nonperiodic, b, 0, s);
        for (size_t r = 0; r < 4; ++r) EXPECT_EQ(x[r].position, y[r].position);
        EXPECT_EQ(evaluate(x.data(), 0.0f).position, pinned.points[static_cast<size_t>(3 * s)]);
    }
}

TEST(BasisConversion, LinearCurvesPassThroughTheirPointsAndAreLinear) {
    for (CurveWrap wrap : {CurveWrap::Nonperiodic, CurveWrap::Periodic}) {
        const CurveKind kind{CurveType::Linear, CurveBasis::CatmullRom, wrap};  // basis ignored
        const CurvesPrim prim = randomPrim(kind, {5}, 11);
        const CurveTopology topology(prim);
        const int spans = topology.segmentCount(0);
        ASSERT_EQ(spans, wrap == CurveWrap::Periodic ? 5 : 4);
        for (int s = 0; s < spans; ++s) {
            const glm::vec3 a = prim.points[static_cast<size_t>(s)];
            const glm::vec3 b = prim.points[static_cast<size_t>((s + 1) % 5)];
            const auto controls = convertedSpan(prim, topology, 0, s);
            for (int i = 0; i <= 8; ++i) {
                const float u = static_cast<float>(i) / 8.0f;
                const std::string what = std::string(toString(wrap)) + " span " + std::to_string(s);
                expectNear(glm::dvec3(evaluate(controls.data(), u).position), glm::dvec3(a + u * (b - a)), 1e-6, what);
                expectNear(glm::dvec3(evaluateTangent(controls.data(), u)), glm::dvec3(b - a), 1e-5, what);
            }
        }
    }
}

TEST(BasisConversion, LinearSpanStencilWrapsOnlyWhenPeriodic) {
    const float values[3] = {1.0f, 2.0f, 4.0f};
    float out[4];
    applyStencil(linearSpanStencil(3, true, 2), values, 1, out);
    EXPECT_EQ((std::array<float, 4>{out[0], out[1], out[2], out[3]}), (std::array<float, 4>{7.0f, 4.0f, 1.0f, -2.0f}));
    applyStencil(linearSpanStencil(3, false, 1), values, 1, out);
    EXPECT_EQ((std::array<float, 4>{out[0], out[1], out[2], out[3]}), (std::array<float, 4>{0.0f, 2.0f, 4.0f, 6.0f}));
}
