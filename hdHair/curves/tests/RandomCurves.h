#pragma once
// Random curves for the curves tests: one place that builds them, so that a
// seed gives the same points in every test that uses it.

#include <random>
#include <vector>

#include "hdHair/curves/CurveTopology.h"
#include "hdHair/scene/CurvesPrim.h"

namespace hdhair::test {

// A prim at /World/hair with the given curves, its points uniform in [-1, 1]^3.
inline CurvesPrim randomPrim(const CurveKind& kind, const std::vector<int>& counts, unsigned seed) {
    CurvesPrim prim;
    prim.path = "/World/hair";
    prim.type = kind.type;
    prim.basis = kind.basis;
    prim.wrap = kind.wrap;
    prim.curveVertexCounts = counts;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> coordinate(-1.0f, 1.0f);
    int total = 0;
    for (int n : counts) total += n;
    for (int i = 0; i < total; ++i) prim.points.emplace_back(coordinate(rng), coordinate(rng), coordinate(rng));
    return prim;
}

inline CurvesPrim randomPrim(CurveType type, CurveBasis basis, CurveWrap wrap, const std::vector<int>& counts,
                             unsigned seed) {
    CurveKind kind;
    kind.type = type;
    kind.basis = basis;
    kind.wrap = wrap;
    return randomPrim(kind, counts, seed);
}

}  // namespace hdhair::test
