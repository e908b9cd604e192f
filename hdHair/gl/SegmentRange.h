#pragma once
// Segments [first, first + count) of the strand geometry (StrandGeometry):
// the range a prim owns, or one that a draw covers.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace hdhair::gl {

struct SegmentRange {
    uint64_t first = 0, count = 0;
    bool operator==(const SegmentRange& other) const { return first == other.first && count == other.count; }
};

// `ranges` in order, empty ones left out and each joined to the one before
// where they lie back to back (drawn prims mostly do, and each range costs a
// draw or a dispatch).
std::vector<SegmentRange> joinedRanges(const std::vector<SegmentRange>& ranges);

// `ranges` cut, in order, into consecutive pieces of `pieceSegments` segments
// (the last may hold fewer); one piece holding them all when pieceSegments
// is 0. Drawing the pieces one after the other draws what the ranges do.
std::vector<std::vector<SegmentRange>> piecesOf(const std::vector<SegmentRange>& ranges, size_t pieceSegments);

}  // namespace hdhair::gl
