#include "hdHair/curves/BasisConversion.h"

#include <algorithm>
#include <cassert>

namespace hdhair {

namespace {

// Rows derived in BasisConversion.h (and README.md): each row is one CR control.
constexpr BasisMatrix kFromBezier{{
    {6.0, -6.0, 0.0, 1.0},  // C0 = B3 - 6(B1 - B0)
    {1.0, 0.0, 0.0, 0.0},   // C1 = B0
    {0.0, 0.0, 0.0, 1.0},   // C2 = B3
    {1.0, 0.0, -6.0, 6.0},  // C3 = B0 + 6(B3 - B2)
}};
constexpr BasisMatrix kFromBspline{{
    {1.0, 1.0 / 6.0, -1.0 / 3.0, 1.0 / 6.0},  // C0 = E - (Q2 - Q0)
    {1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0, 0.0},   // C1 = S = (Q0 + 4Q1 + Q2) / 6
    {0.0, 1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0},   // C2 = E = (Q1 + 4Q2 + Q3) / 6
    {1.0 / 6.0, -1.0 / 3.0, 1.0 / 6.0, 1.0},  // C3 = S + (Q3 - Q1)
}};
constexpr BasisMatrix kIdentity{{
    {1.0, 0.0, 0.0, 0.0},
    {0.0, 1.0, 0.0, 0.0},
    {0.0, 0.0, 1.0, 0.0},
    {0.0, 0.0, 0.0, 1.0},
}};
// Linear span a->b as CR controls (2a-b, a, b, 2b-a); columns are (a, b).
constexpr std::array<std::array<double, 2>, 4> kFromLinear{{
    {2.0, -1.0},
    {1.0, 0.0},
    {0.0, 1.0},
    {-1.0, 2.0},
}};

// A source control: a vertex, or a phantom end point made of two vertices.
struct Source {
    SpanStencil::Term terms[2];
    int termCount = 1;
};

Source vertexSource(int vertex) {
    Source source;
    source.terms[0] = {vertex, 1.0};
    return source;
}

// Adds weight * source to a control, merging terms that name the same vertex
// (clamped and wrapped spans repeat vertices).
void accumulate(SpanStencil::Control& control, const Source& source, double weight) {
    if (weight == 0.0) return;
    for (int s = 0; s < source.termCount; ++s) {
        const SpanStencil::Term& term = source.terms[s];
        SpanStencil::Term* end = control.terms.data() + control.termCount;
        SpanStencil::Term* found = std::find_if(control.terms.data(), end,
                                                [&](const SpanStencil::Term& t) { return t.vertex == term.vertex; });
        if (found != end) {
            found->weight += weight * term.weight;
        } else {
            assert(control.termCount < SpanStencil::kMaxTerms);
            *found = {term.vertex, weight * term.weight};
            ++control.termCount;
        }
    }
}

// The cubic source control at position `index` of a curve of n vertices: the
// wrap rules of BasisConversion.h.
Source cubicSource(const CurveKind& kind, int n, int index) {
    if (kind.isPeriodic()) return vertexSource(((index % n) + n) % n);
    if (kind.hasPhantomEnds()) {
        Source phantom;
        phantom.termCount = 2;
        if (index < 0) {  // P[-1] = 2 P0 - P1
            phantom.terms[0] = {0, 2.0};
            phantom.terms[1] = {1, -1.0};
            return phantom;
        }
        if (index >= n) {  // P[n] = 2 P[n-1] - P[n-2]
            phantom.terms[0] = {n - 1, 2.0};
            phantom.terms[1] = {n - 2, -1.0};
            return phantom;
        }
        return vertexSource(index);
    }
    return vertexSource(std::min(index, n - 1));  // HdSt: repeat the last vertex
}

SpanStencil linearStencilFor(int a, int b) {
    SpanStencil stencil;
    const Source sources[2] = {vertexSource(a), vertexSource(b)};
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 2; ++c) accumulate(stencil.controls[r], sources[c], kFromLinear[r][c]);
    return stencil;
}

}  // namespace

const BasisMatrix& catmullRomFromBasis(CurveBasis basis) {
    switch (basis) {
    case CurveBasis::Bezier: return kFromBezier;
    case CurveBasis::Bspline: return kFromBspline;
    case CurveBasis::CatmullRom: return kIdentity;
    }
    return kIdentity;
}

SpanStencil linearSpanStencil(int count, bool periodic, int span) {
    assert(count >= 1 && span >= 0);
    const int a = std::min(span, count - 1);
    const int b = periodic ? (span + 1) % count : std::min(span + 1, count - 1);
    return linearStencilFor(a, b);
}

namespace {

bool sameControl(const SpanStencil::Control& a, const SpanStencil::Control& b) {
    if (a.termCount != b.termCount) return false;
    for (int t = 0; t < a.termCount; ++t)
        if (a.terms[size_t(t)].vertex != b.terms[size_t(t)].vertex || a.terms[size_t(t)].weight != b.terms[size_t(t)].weight)
            return false;
    return true;
}

}  // namespace

bool spansShareControls(const CurveKind& kind, int n) {
    const int spans = segmentCount(kind, n);
    if (spans <= 1) return true;
    SpanStencil previous = catmullRomStencil(kind, n, 0);
    for (int s = 1; s < spans; ++s) {
        SpanStencil next = catmullRomStencil(kind, n, s);
        for (size_t r = 0; r < 3; ++r)
            if (!sameControl(previous.controls[r + 1], next.controls[r])) return false;
        previous = next;
    }
    return true;
}

SpanStencil catmullRomStencil(const CurveKind& kind, int n, int span) {
    assert(n >= 1 && span >= 0);
    if (kind.isLinear()) return linearSpanStencil(n, kind.isPeriodic(), span);

    const int first = kind.hasPhantomEnds() ? span - 1 : span * vertexStep(kind.basis);
    Source sources[4];
    for (int v = 0; v < 4; ++v) sources[v] = cubicSource(kind, n, first + v);

    const BasisMatrix& matrix = catmullRomFromBasis(kind.basis);
    SpanStencil stencil;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) accumulate(stencil.controls[r], sources[c], matrix[r][c]);
    return stencil;
}

void applyStencil(const SpanStencil& stencil, const float* curveValues, int tupleSize, float* out) {
    for (int r = 0; r < 4; ++r) {
        const SpanStencil::Control& control = stencil.controls[r];
        for (int k = 0; k < tupleSize; ++k) {
            double sum = 0.0;
            for (int t = 0; t < control.termCount; ++t) {
                const SpanStencil::Term& term = control.terms[t];
                sum += term.weight * static_cast<double>(curveValues[term.vertex * tupleSize + k]);
            }
            out[r * tupleSize + k] = static_cast<float>(sum);
        }
    }
}

}  // namespace hdhair
