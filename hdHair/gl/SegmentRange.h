#pragma once
// Segments [first, first + count) of the strand geometry (StrandGeometry):
// the range a prim owns, or one that a draw covers.

#include <cstdint>

namespace hdhair::gl {

struct SegmentRange {
    uint64_t first = 0, count = 0;
    bool operator==(const SegmentRange& other) const { return first == other.first && count == other.count; }
};

}  // namespace hdhair::gl
