#pragma once
// Exact change of basis of one span to uniform Catmull-Rom controls (tension
// 0.5: the span runs from C1 to C2 with end tangents (C2-C0)/2 and (C3-C1)/2).
// Every cubic with the same end points and end tangents is the same cubic, so
// matching those is exact:
//  - bezier B0..B3:     C1 = B0, C2 = B3, C0 = B3 - 6(B1-B0), C3 = B0 + 6(B3-B2)
//  - bspline Q0..Q3:    S = (Q0+4Q1+Q2)/6, E = (Q1+4Q2+Q3)/6,
//                       C1 = S, C2 = E, C0 = E - (Q2-Q0), C3 = S + (Q3-Q1)
//  - catmullRom:        identity
//  - linear span a->b:  (2a-b, a, b, 2b-a), reproduced exactly by CR's linear precision
// Every row of these matrices sums to 1, so the conversion commutes with affine
// transforms and applies equally to points and to any vertex primvar.
//
// A span's source controls come from the curve's vertices by the wrap rules:
//  - nonperiodic: span s uses vertices s*vstep .. s*vstep+3, clamped to the
//    last vertex when the curve is under-length (as HdSt does);
//  - periodic: indices wrap modulo n, so the last span closes onto the first
//    vertices (periodic bezier spans start at 0, 3, 6, ...);
//  - pinned bspline/catmullRom: the UsdGeomBasisCurves spec's phantom points
//    P[-1] = 2P0 - P1 and P[n] = 2P[n-1] - P[n-2] are added (reflection), and
//    span s uses P[s-1] .. P[s+2], s = 0 .. n-2. Both bases then start exactly
//    at P0 and end at P[n-1]: for bspline (P[-1] + 4P0 + P1)/6 = P0. HdSt
//    instead repeats the end points (once for catmullRom, twice for bspline),
//    which gives a different shape near the ends and two more bspline spans;
//    we follow the spec and USD's segment count (n-1).
// Pinned bezier and pinned linear curves are nonperiodic.

#include <array>

#include "hdHair/curves/CurveTopology.h"

namespace hdhair {

// A 4x4 change-of-basis matrix: Catmull-Rom control r = sum_c m[r][c] * source c.
using BasisMatrix = std::array<std::array<double, 4>, 4>;

// The matrix from `basis` controls to Catmull-Rom controls (identity for catmullRom).
const BasisMatrix& catmullRomFromBasis(CurveBasis basis);

// One span's four Catmull-Rom controls, each a weighted sum of the curve's
// vertices (indices relative to the curve's first vertex). Computed once per
// span and applied to positions and to every vertex primvar alike.
struct SpanStencil {
    static constexpr int kMaxTerms = 8;  // 4 sources, each at most 2 vertices (phantoms)
    struct Term {
        int vertex = 0;
        double weight = 0.0;
    };
    struct Control {
        std::array<Term, kMaxTerms> terms{};
        int termCount = 0;
    };
    std::array<Control, 4> controls{};
};

// The stencil of span `span` (0 <= span < segmentCount(kind, n)) of a curve
// with n vertices, for any type, basis and wrap.
SpanStencil catmullRomStencil(const CurveKind& kind, int n, int span);

// The stencil of a linear span from value[span] to value[span+1] of `count`
// values (wrapping to value[0] when periodic): (2a-b, a, b, 2b-a). Used for
// linear curves and for varying primvars, which are linear between span ends.
SpanStencil linearSpanStencil(int count, bool periodic, int span);

// True when each span's last three controls are the next span's first three,
// term for term, for every span of a curve with n vertices: the spans can then
// share one control polygon (PreparedCurves). Holds for Catmull-Rom curves of
// any wrap (phantoms included); not for bezier, bspline or linear, whose
// converted controls are combinations local to each span.
bool spansShareControls(const CurveKind& kind, int n);

// Writes the 4 controls (4 * tupleSize floats, control-major) that `stencil`
// makes of one curve's values (element-major, tupleSize floats per vertex).
// Reads only the vertices the stencil names; computes in double precision.
void applyStencil(const SpanStencil& stencil, const float* curveValues, int tupleSize, float* out);

}  // namespace hdhair
