#pragma once
// A CPU reference for the curve a BasisCurves prim describes: it evaluates a
// span directly in its authored basis (Bernstein for bezier, the uniform cubic
// B-spline matrix, the Catmull-Rom matrix, or linear interpolation) with the
// wrap rules spelled out independently of BasisConversion, so that tests can
// check the conversion against it. Slow by design (one vertex fetch per term);
// not used for rendering.

#include <cstddef>

#include <glm/vec3.hpp>

#include "hdHair/curves/CurveTopology.h"

namespace hdhair {

class ReferenceCurveEvaluator {
public:
    // Keeps a reference to `prim`, which must outlive the evaluator.
    explicit ReferenceCurveEvaluator(const CurvesPrim& prim);

    const CurveTopology& topology() const { return topology_; }
    size_t curveCount() const { return topology_.curveCount(); }
    int spanCount(size_t curve) const { return topology_.segmentCount(curve); }

    // Object-space position and its derivative d/du at u in [0, 1] of a span.
    glm::dvec3 position(size_t curve, int span, double u) const;
    glm::dvec3 derivative(size_t curve, int span, double u) const;

    // Any vertex-rate data of the whole prim (tupleSize floats per vertex, in
    // points order) at the same parameter; writes tupleSize doubles to `out`.
    // With `derivative`, writes d/du instead.
    void evaluate(const float* vertexValues, int tupleSize, size_t curve, int span, double u, double* out,
                  bool derivative = false) const;

private:
    const CurvesPrim& prim_;
    CurveTopology topology_;
};

}  // namespace hdhair
