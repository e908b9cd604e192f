#pragma once
// Per-curve element counts of a BasisCurves prim, following what USD and
// Hydra *implement* (the sources named below), which is not always what
// the UsdGeomBasisCurves class doc tables say:
//  - segments: UsdGeomBasisCurves::ComputeSegmentCounts for valid curves, and
//    HdSt's index builder (basisCurvesComputations.cpp) for under-length ones;
//  - varying: Hd's CalculateNeededNumberOfVaryingControlPoints and UsdGeom's
//    _ComputeVaryingDataSize (pinned curves use the nonperiodic size).
// vstep (the vertex step between cubic segments) is bezier 3, bspline 1,
// catmullRom 1 (_GetVStepForBasis in pxr/usd/usdGeom/basisCurves.cpp).

#include <cstddef>
#include <string>
#include <vector>

#include "hdHair/scene/CurvesPrim.h"

namespace hdhair {

// The (type, basis, wrap) triple that decides how a curve's vertices make spans.
struct CurveKind {
    CurveType type = CurveType::Cubic;
    CurveBasis basis = CurveBasis::Bezier;
    CurveWrap wrap = CurveWrap::Nonperiodic;

    bool isLinear() const { return type == CurveType::Linear; }
    bool isPeriodic() const { return wrap == CurveWrap::Periodic; }
    // Pinned changes only cubic bspline and catmullRom curves: they gain the
    // spec's phantom end points. Pinned bezier and pinned linear curves are
    // nonperiodic ones (UsdGeomBasisCurves class doc, "pinned").
    bool hasPhantomEnds() const {
        return type == CurveType::Cubic && wrap == CurveWrap::Pinned && basis != CurveBasis::Bezier;
    }
};

std::string toString(const CurveKind& kind);  // "cubic bspline pinned", "linear periodic"

// 3 for bezier, 1 for bspline and catmullRom.
int vertexStep(CurveBasis basis);

// Number of spans drawn for a curve of n vertices. Matches USD's segment counts
// for valid n (cubic pinned bspline/catmullRom: n-1); for under-length cubic
// curves it is HdSt's count (nonperiodic max(n-4,0)/vstep+1, periodic
// max(n/vstep,1)), and 0 for cubic n < 2, which HdSt skips.
int segmentCount(const CurveKind& kind, int n);

// Number of varying values USD expects to be authored for the curve: linear n;
// cubic nonperiodic and pinned max(n-4,0)/vstep+2; cubic periodic
// max(n/vstep,1); 0 for n < 1 (Hd skips such curves).
int varyingCount(const CurveKind& kind, int n);

// Number of varying values after resolution: one per span end (per span for
// periodic curves, whose last span ends where the first starts). Equals
// varyingCount except for pinned bspline/catmullRom curves with n >= 2, whose
// n-1 spans need n values: the two phantom-end spans get values of their own.
int spanEndCount(const CurveKind& kind, int n);

// Validity from the UsdGeomBasisCurves class doc: cubic nonperiodic n >= 4 and
// (n-4) % vstep == 0; cubic periodic n % vstep == 0 (and n >= 3, to close a
// curve); pinned bspline/catmullRom n >= 2; linear nonperiodic n >= 2; linear
// periodic n >= 3 (the doc's "n > 2" / "n > 3" are off by one, guide §3.6).
bool isValidVertexCount(const CurveKind& kind, int n);

// The rule above in words, for warnings: "4 + 3k vertices (k >= 0)".
std::string describeVertexCountRule(const CurveKind& kind);

// Counts and prefix-sum offsets of every curve of a prim. Offsets have
// curveCount()+1 entries, so curve i owns [offsets[i], offsets[i+1]).
struct CurveTopology {
    CurveKind kind;
    std::vector<int> vertexCounts;       // as authored, negative counts read as 0
    std::vector<size_t> vertexOffsets;   // into points and vertex primvars
    std::vector<size_t> varyingOffsets;  // into authored varying primvars (varyingCount)
    std::vector<size_t> spanEndOffsets;  // into resolved varying primvars (spanEndCount)
    std::vector<size_t> segmentOffsets;  // spans of every curve, dropped or not

    CurveTopology() : CurveTopology(CurveKind{}, {}) {}
    CurveTopology(const CurveKind& curveKind, std::vector<int> counts);
    explicit CurveTopology(const CurvesPrim& prim);

    size_t curveCount() const { return vertexCounts.size(); }
    size_t vertexTotal() const { return vertexOffsets.back(); }
    size_t varyingTotal() const { return varyingOffsets.back(); }
    size_t spanEndTotal() const { return spanEndOffsets.back(); }
    size_t segmentTotal() const { return segmentOffsets.back(); }

    int vertexCount(size_t curve) const { return vertexCounts[curve]; }
    int segmentCount(size_t curve) const { return static_cast<int>(segmentOffsets[curve + 1] - segmentOffsets[curve]); }
    int spanEndCount(size_t curve) const { return static_cast<int>(spanEndOffsets[curve + 1] - spanEndOffsets[curve]); }
};

}  // namespace hdhair
