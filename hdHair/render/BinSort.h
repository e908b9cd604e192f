#pragma once
// Bin sorting of strand segments by view depth (Kim & Neumann 2002, as used
// by Svoboda 2012, section 2.5.1): the depth range of the hair is cut into N
// slabs perpendicular to the view direction, each segment goes into the slab
// holding its FARTHER end point, and slabs are drawn far to near. O(n) in the
// number of segments, independent of N (two counting sorts).
//
// Within a slab the order is a hash of the segment's geometry (then the
// geometry itself, where distinct segments share a hash), not the order the
// curves were authored in: shuffling a stage's curves (or Hydra syncing prims
// in another order) gives the same image. Only identical segments keep their
// input order.
//
// CPU (TBB) rather than a GPU compute pass, by measurement: see
// hdHair/render/README.md ("Bin sorting: CPU or GPU").

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "hdHair/curves/PreparedCurves.h"

namespace hdhair {

struct BinSortStatistics {
    double nearDepth = 0.0, farDepth = 0.0;  // the range cut into bins
    uint32_t occupiedBins = 0;
};

// The within-bin sort key of each segment (a 16-bit hash of its end
// points), computed once when a prim is prepared rather than every frame.
std::vector<uint16_t> segmentSortHashes(const PreparedCurves& curves);

// One prim's segments as the sort sees them: segment s spans
// controlPoints[firstControl[s] + 1] to controlPoints[firstControl[s] + 2],
// has hashes[s], and is segment first + s of the frame's geometry.
struct SortSpan {
    const StrandControlPoint* controlPoints = nullptr;
    const uint32_t* firstControl = nullptr;
    const uint16_t* hashes = nullptr;
    size_t segments = 0;
    uint64_t first = 0;
};

// Depth is measured along `viewDirection` (unit) from `cameraPosition`.
// Writes the frame's segment indices (first + s), far to near, into `order`.
void binSortSegments(const std::vector<SortSpan>& spans, const glm::dvec3& cameraPosition,
                     const glm::dvec3& viewDirection, uint32_t binCount, std::vector<uint32_t>& order,
                     BinSortStatistics* statistics = nullptr);

// The same for one prim's segments numbered from 0 (tests and benchmarks):
// hashes computed here.
void binSortSegments(const PreparedCurves& curves, const glm::dvec3& cameraPosition,
                     const glm::dvec3& viewDirection, uint32_t binCount, std::vector<uint32_t>& order,
                     BinSortStatistics* statistics = nullptr);

}  // namespace hdhair
