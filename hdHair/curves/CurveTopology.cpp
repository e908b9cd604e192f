#include "hdHair/curves/CurveTopology.h"

#include <algorithm>
#include <utility>

namespace hdhair {

std::string toString(const CurveKind& kind) {
    if (kind.isLinear()) return std::string("linear ") + toString(kind.wrap);
    return std::string("cubic ") + toString(kind.basis) + " " + toString(kind.wrap);
}

int vertexStep(CurveBasis basis) { return basis == CurveBasis::Bezier ? 3 : 1; }

int segmentCount(const CurveKind& kind, int n) {
    if (kind.isLinear()) {
        if (kind.isPeriodic()) return n >= 2 ? n : 0;
        return std::max(n - 1, 0);
    }
    if (n < 2) return 0;  // HdSt's _BuildCubicIndexArray skips these
    const int vstep = vertexStep(kind.basis);
    if (kind.isPeriodic()) return std::max(n / vstep, 1);
    // Phantom P[-1] and P[n] make n+2 bspline/catmullRom vertices, hence
    // (n+2-4)/1+1 = n-1 spans (ComputeSegmentCounts).
    if (kind.hasPhantomEnds()) return n - 1;
    return std::max(n - 4, 0) / vstep + 1;
}

int varyingCount(const CurveKind& kind, int n) {
    if (n < 1) return 0;
    if (kind.isLinear()) return n;
    const int vstep = vertexStep(kind.basis);
    if (kind.isPeriodic()) return std::max(n / vstep, 1);
    // Pinned uses the nonperiodic size: "data for the additional segment(s)
    // ... doesn't need to be authored" (pxr/usd/usdGeom/basisCurves.cpp).
    return std::max(n - 4, 0) / vstep + 2;
}

int spanEndCount(const CurveKind& kind, int n) {
    if (kind.hasPhantomEnds() && n >= 2) return segmentCount(kind, n) + 1;
    return varyingCount(kind, n);
}

bool isValidVertexCount(const CurveKind& kind, int n) {
    if (kind.isLinear()) return kind.isPeriodic() ? n >= 3 : n >= 2;
    if (kind.hasPhantomEnds()) return n >= 2;
    const int vstep = vertexStep(kind.basis);
    if (kind.isPeriodic()) return n >= 3 && n % vstep == 0;
    return n >= 4 && (n - 4) % vstep == 0;
}

std::string describeVertexCountRule(const CurveKind& kind) {
    if (kind.isLinear()) return kind.isPeriodic() ? "at least 3 vertices" : "at least 2 vertices";
    if (kind.hasPhantomEnds()) return "at least 2 vertices";
    const bool bezier = kind.basis == CurveBasis::Bezier;
    if (kind.isPeriodic()) return bezier ? "a multiple of 3 vertices (at least 3)" : "at least 3 vertices";
    return bezier ? "4 + 3k vertices (k >= 0)" : "at least 4 vertices";
}

CurveTopology::CurveTopology(const CurveKind& curveKind, std::vector<int> counts)
    : kind(curveKind), vertexCounts(std::move(counts)) {
    const size_t curves = vertexCounts.size();
    vertexOffsets.assign(curves + 1, 0);
    varyingOffsets.assign(curves + 1, 0);
    spanEndOffsets.assign(curves + 1, 0);
    segmentOffsets.assign(curves + 1, 0);
    for (size_t i = 0; i < curves; ++i) {
        int& n = vertexCounts[i];
        n = std::max(n, 0);
        vertexOffsets[i + 1] = vertexOffsets[i] + static_cast<size_t>(n);
        varyingOffsets[i + 1] = varyingOffsets[i] + static_cast<size_t>(varyingCount(kind, n));
        spanEndOffsets[i + 1] = spanEndOffsets[i] + static_cast<size_t>(hdhair::spanEndCount(kind, n));
        segmentOffsets[i + 1] = segmentOffsets[i] + static_cast<size_t>(hdhair::segmentCount(kind, n));
    }
}

CurveTopology::CurveTopology(const CurvesPrim& prim)
    : CurveTopology(CurveKind{prim.type, prim.basis, prim.wrap}, prim.curveVertexCounts) {}

}  // namespace hdhair
