#include "hdHair/curves/ReferenceCurveEvaluator.h"

#include <algorithm>
#include <array>
#include <cassert>

#include <glm/gtc/type_ptr.hpp>

namespace hdhair {

namespace {

using Weights = std::array<double, 4>;

// Cubic basis functions of the four span controls at u, or their derivatives.
Weights bezierWeights(double u, bool derivative) {
    const double s = 1.0 - u;
    if (derivative) return {-3.0 * s * s, 3.0 * s * s - 6.0 * u * s, 6.0 * u * s - 3.0 * u * u, 3.0 * u * u};
    return {s * s * s, 3.0 * u * s * s, 3.0 * u * u * s, u * u * u};
}

// Uniform cubic B-spline: (1/6) [u^3 u^2 u 1] [-1 3 -3 1; 3 -6 3 0; -3 0 3 0; 1 4 1 0].
Weights bsplineWeights(double u, bool derivative) {
    const double s = 1.0 - u;
    if (derivative) return {-0.5 * s * s, 1.5 * u * u - 2.0 * u, -1.5 * u * u + u + 0.5, 0.5 * u * u};
    return {s * s * s / 6.0, (3.0 * u * u * u - 6.0 * u * u + 4.0) / 6.0,
            (-3.0 * u * u * u + 3.0 * u * u + 3.0 * u + 1.0) / 6.0, u * u * u / 6.0};
}

// Catmull-Rom, tension 0.5: (1/2) [u^3 u^2 u 1] [-1 3 -3 1; 2 -5 4 -1; -1 0 1 0; 0 2 0 0].
Weights catmullRomWeights(double u, bool derivative) {
    const std::array<std::array<double, 4>, 4> m{{
        {-1.0, 3.0, -3.0, 1.0},
        {2.0, -5.0, 4.0, -1.0},
        {-1.0, 0.0, 1.0, 0.0},
        {0.0, 2.0, 0.0, 0.0},
    }};
    const std::array<double, 4> powers = derivative ? std::array<double, 4>{3.0 * u * u, 2.0 * u, 1.0, 0.0}
                                                    : std::array<double, 4>{u * u * u, u * u, u, 1.0};
    Weights w{};
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) w[c] += 0.5 * powers[r] * m[r][c];
    return w;
}

Weights cubicWeights(CurveBasis basis, double u, bool derivative) {
    switch (basis) {
    case CurveBasis::Bezier: return bezierWeights(u, derivative);
    case CurveBasis::Bspline: return bsplineWeights(u, derivative);
    case CurveBasis::CatmullRom: return catmullRomWeights(u, derivative);
    }
    return bezierWeights(u, derivative);
}

}  // namespace

ReferenceCurveEvaluator::ReferenceCurveEvaluator(const CurvesPrim& prim) : prim_(prim), topology_(prim) {}

void ReferenceCurveEvaluator::evaluate(const float* vertexValues, int tupleSize, size_t curve, int span, double u,
                                       double* out, bool derivative) const {
    assert(span >= 0 && span < spanCount(curve));
    const CurveKind& kind = topology_.kind;
    const int n = topology_.vertexCount(curve);
    const size_t tuple = static_cast<size_t>(tupleSize);
    const float* first = vertexValues + topology_.vertexOffsets[curve] * tuple;
    auto vertex = [&](int i, size_t c) { return static_cast<double>(first[static_cast<size_t>(i) * tuple + c]); };

    if (kind.isLinear()) {
        const int a = span;
        const int b = kind.isPeriodic() ? (span + 1) % n : span + 1;
        for (size_t c = 0; c < tuple; ++c) {
            out[c] = derivative ? vertex(b, c) - vertex(a, c) : (1.0 - u) * vertex(a, c) + u * vertex(b, c);
        }
        return;
    }

    // Control j of the span, component c, by the wrap rules: the UsdGeom
    // spec's reflected phantoms for pinned bspline/catmullRom, wrap for
    // periodic, HdSt's clamp to the last vertex for under-length nonperiodic.
    const int start = kind.hasPhantomEnds() ? span - 1 : span * vertexStep(kind.basis);
    auto control = [&](int j, size_t c) {
        if (kind.isPeriodic()) return vertex(j % n, c);
        if (kind.hasPhantomEnds()) {
            if (j < 0) return 2.0 * vertex(0, c) - vertex(1, c);
            if (j >= n) return 2.0 * vertex(n - 1, c) - vertex(n - 2, c);
            return vertex(j, c);
        }
        return vertex(std::min(j, n - 1), c);
    };
    const Weights w = cubicWeights(kind.basis, u, derivative);
    for (size_t c = 0; c < tuple; ++c) {
        out[c] = 0.0;
        for (int j = 0; j < 4; ++j) out[c] += w[static_cast<size_t>(j)] * control(start + j, c);
    }
}

glm::dvec3 ReferenceCurveEvaluator::position(size_t curve, int span, double u) const {
    assert(topology_.vertexOffsets[curve + 1] <= prim_.points.size());
    glm::dvec3 result;
    evaluate(glm::value_ptr(prim_.points.front()), 3, curve, span, u, glm::value_ptr(result));
    return result;
}

glm::dvec3 ReferenceCurveEvaluator::derivative(size_t curve, int span, double u) const {
    assert(topology_.vertexOffsets[curve + 1] <= prim_.points.size());
    glm::dvec3 result;
    evaluate(glm::value_ptr(prim_.points.front()), 3, curve, span, u, glm::value_ptr(result), true);
    return result;
}

}  // namespace hdhair
