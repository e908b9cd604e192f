#include "hdHair/gl/SegmentRange.h"

#include <algorithm>

namespace hdhair::gl {

std::vector<SegmentRange> joinedRanges(const std::vector<SegmentRange>& ranges) {
    std::vector<SegmentRange> joined;
    for (const SegmentRange& range : ranges) {
        if (range.count == 0) continue;
        if (!joined.empty() && joined.back().first + joined.back().count == range.first)
            joined.back().count += range.count;
        else
            joined.push_back(range);
    }
    return joined;
}

std::vector<std::vector<SegmentRange>> piecesOf(const std::vector<SegmentRange>& ranges, size_t pieceSegments) {
    std::vector<std::vector<SegmentRange>> pieces;
    if (pieceSegments == 0) {
        pieces.push_back(ranges);
        return pieces;
    }
    std::vector<SegmentRange> piece;
    size_t segments = 0;
    for (const SegmentRange& range : ranges) {
        for (uint64_t first = range.first; first < range.first + range.count;) {
            const uint64_t count = std::min<uint64_t>(range.first + range.count - first, pieceSegments - segments);
            piece.push_back(SegmentRange{first, count});
            segments += count;
            first += count;
            if (segments == pieceSegments) {
                pieces.push_back(std::move(piece));
                piece.clear();
                segments = 0;
            }
        }
    }
    if (!piece.empty()) pieces.push_back(std::move(piece));
    return pieces;
}

}  // namespace hdhair::gl
