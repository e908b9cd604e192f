#include "hdHair/render/BinSort.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <tuple>

#include <glm/geometric.hpp>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "hdHair/render/CountingSort.h"

namespace hdhair {
namespace {

constexpr uint32_t kHashBuckets = 1u << 16;

uint32_t floatBits(float value) {
    uint32_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    return bits;
}

// 16 bits from the segment's end points (a murmur3-style finaliser mixes
// them); equal segments collide, which leaves them in input order.
uint16_t geometryHash(const StrandControlPoint& a, const StrandControlPoint& b) {
    uint32_t h = 0x9e3779b9u;
    const float values[6] = {a.position.x, a.position.y, a.position.z, b.position.x, b.position.y, b.position.z};
    for (float value : values) {
        h ^= floatBits(value);
        h *= 0x85ebca6bu;
        h ^= h >> 13;
        h *= 0xc2b2ae35u;
        h ^= h >> 16;
    }
    return uint16_t(h & (kHashBuckets - 1u));
}

// The spans' segments numbered 0..n-1 here; `start` finds each one's
// control points and `global` its index in the frame.
struct NumberedSegments {
    std::vector<const StrandControlPoint*> start;
    std::vector<uint32_t> global;
    std::vector<uint16_t> hash;
    size_t size() const { return start.size(); }
};

// Every span's segments, numbered in span order.
NumberedSegments numberSegments(const std::vector<SortSpan>& spans) {
    size_t segments = 0;
    for (const SortSpan& span : spans) segments += span.segments;
    NumberedSegments numbered;
    std::vector<const StrandControlPoint*>& start = numbered.start;
    std::vector<uint32_t>& global = numbered.global;
    std::vector<uint16_t>& hash = numbered.hash;
    start.resize(segments);
    global.resize(segments);
    hash.resize(segments);
    std::vector<size_t> offsets(spans.size() + 1, 0);
    for (size_t i = 0; i < spans.size(); ++i) offsets[i + 1] = offsets[i] + spans[i].segments;
    tbb::parallel_for(size_t(0), spans.size(), [&](size_t i) {
        const SortSpan& span = spans[i];
        tbb::parallel_for(tbb::blocked_range<size_t>(0, span.segments), [&](const tbb::blocked_range<size_t>& r) {
            for (size_t s = r.begin(); s != r.end(); ++s) {
                start[offsets[i] + s] = span.controlPoints + span.firstControl[s];
                global[offsets[i] + s] = uint32_t(span.first + s);
                hash[offsets[i] + s] = span.hashes[s];
            }
        });
    });
    return numbered;
}

// Each segment's depth along `viewDirection`.
std::vector<float> segmentDepths(const std::vector<const StrandControlPoint*>& start, const glm::dvec3& cameraPosition,
                                 const glm::dvec3& viewDirection) {
    std::vector<float> depth(start.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, start.size()), [&](const tbb::blocked_range<size_t>& range) {
        for (size_t s = range.begin(); s != range.end(); ++s) {
            double d0 = glm::dot(glm::dvec3(start[s][1].position) - cameraPosition, viewDirection);
            double d1 = glm::dot(glm::dvec3(start[s][2].position) - cameraPosition, viewDirection);
            depth[s] = float(std::max(d0, d1));  // binned by the farther end point
        }
    });
    return depth;
}

using DepthRange = std::pair<float, float>;

// The smallest and largest depth; (max float, lowest float) when there are none.
DepthRange depthRange(const std::vector<float>& depth) {
    return tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, depth.size()),
        DepthRange(std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest()),
        [&](const tbb::blocked_range<size_t>& r, DepthRange value) {
            for (size_t s = r.begin(); s != r.end(); ++s) {
                value.first = std::min(value.first, depth[s]);
                value.second = std::max(value.second, depth[s]);
            }
            return value;
        },
        [](DepthRange a, DepthRange b) {
            return DepthRange(std::min(a.first, b.first), std::max(a.second, b.second));
        });
}

// Each segment's bin, as a key that ascends from far to near.
std::vector<uint32_t> binKeys(const std::vector<float>& depth, const DepthRange& range, uint32_t binCount) {
    // Bin i = floor(N (D - Dmin) / (Dmax - Dmin)), clamped to N - 1, numbered
    // so that ascending key means far to near.
    std::vector<uint32_t> key(depth.size());
    const double span = double(range.second) - double(range.first);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, depth.size()), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t s = r.begin(); s != r.end(); ++s) {
            double t = span > 0.0 ? (double(depth[s]) - double(range.first)) / span : 0.0;
            uint32_t bin = std::min(uint32_t(std::max(t, 0.0) * binCount), binCount - 1);
            key[s] = binCount - 1 - bin;
        }
    });
    return key;
}

// Writes into `order` the segments sorted by key, then (within a key) by hash.
void sortByKeyThenHash(const std::vector<uint16_t>& hash, const std::vector<uint32_t>& key, uint32_t binCount,
                       std::vector<uint32_t>& order) {
    // Least significant key first: the hash, then (stably) the bin.
    const size_t segments = key.size();
    std::vector<uint32_t> identity(segments), byHash;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, segments), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t s = r.begin(); s != r.end(); ++s) identity[s] = uint32_t(s);
    });
    stableCountingSort(identity, hash, kHashBuckets, byHash);
    stableCountingSort(byHash, key, binCount, order);
}

// Sorts each run of `order` that shares a key and a hash by the segments' geometry.
void orderHashCollisionsByGeometry(const NumberedSegments& numbered, const std::vector<uint32_t>& key,
                                   std::vector<uint32_t>& order) {
    const std::vector<const StrandControlPoint*>& start = numbered.start;
    const std::vector<uint16_t>& hash = numbered.hash;
    // Distinct segments can share a 16-bit hash (a few dozen pairs in a
    // frame of 30,000 segments); order those by their geometry too, so that
    // input order shows nowhere. Such runs are short: sorting them costs
    // little. Identical segments stay in input order (the sort is stable).
    auto geometryLess = [&](uint32_t x, uint32_t y) {
        const glm::vec3 &xa = start[x][1].position, &xb = start[x][2].position;
        const glm::vec3 &ya = start[y][1].position, &yb = start[y][2].position;
        return std::tie(xa.x, xa.y, xa.z, xb.x, xb.y, xb.z) < std::tie(ya.x, ya.y, ya.z, yb.x, yb.y, yb.z);
    };
    // In parallel: each chunk sorts the runs that start in it.
    auto sameRun = [&](size_t i, size_t j) { return key[order[i]] == key[order[j]] && hash[order[i]] == hash[order[j]]; };
    tbb::parallel_for(tbb::blocked_range<size_t>(0, order.size(), 4096), [&](const tbb::blocked_range<size_t>& chunk) {
        size_t begin = chunk.begin();
        while (begin > 0 && begin < chunk.end() && sameRun(begin - 1, begin)) ++begin;
        while (begin < chunk.end()) {
            size_t end = begin + 1;
            while (end < order.size() && sameRun(begin, end)) ++end;
            if (end - begin > 1) std::stable_sort(order.begin() + long(begin), order.begin() + long(end), geometryLess);
            begin = end;
        }
    });
}

// The depth range and how many bins hold a segment.
void recordStatistics(const DepthRange& range, const std::vector<uint32_t>& key, uint32_t binCount,
                      BinSortStatistics& statistics) {
    const size_t segments = key.size();
    statistics.nearDepth = segments ? range.first : 0.0;
    statistics.farDepth = segments ? range.second : 0.0;
    std::vector<bool> used(binCount, false);
    for (uint32_t k : key) used[k] = true;
    statistics.occupiedBins = uint32_t(std::count(used.begin(), used.end(), true));
}

}  // namespace

std::vector<uint16_t> segmentSortHashes(const PreparedCurves& curves) {
    std::vector<uint16_t> hashes(curves.segmentCount());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, hashes.size()), [&](const tbb::blocked_range<size_t>& range) {
        for (size_t s = range.begin(); s != range.end(); ++s) {
            const StrandControlPoint* controls = curves.spanControls(s);
            hashes[s] = geometryHash(controls[1], controls[2]);
        }
    });
    return hashes;
}

void binSortSegments(const PreparedCurves& curves, const glm::dvec3& cameraPosition, const glm::dvec3& viewDirection,
                     uint32_t binCount, std::vector<uint32_t>& order, BinSortStatistics* statistics) {
    const std::vector<uint16_t> hashes = segmentSortHashes(curves);
    binSortSegments({SortSpan{curves.controlPoints.data(), curves.segmentFirstControl.data(), hashes.data(),
                              hashes.size(), 0}},
                    cameraPosition, viewDirection, binCount, order, statistics);
}

void binSortSegments(const std::vector<SortSpan>& spans, const glm::dvec3& cameraPosition,
                     const glm::dvec3& viewDirection, uint32_t binCount, std::vector<uint32_t>& order,
                     BinSortStatistics* statistics) {
    const NumberedSegments numbered = numberSegments(spans);
    binCount = std::max<uint32_t>(binCount, 1);
    const std::vector<float> depth = segmentDepths(numbered.start, cameraPosition, viewDirection);
    const DepthRange range = depthRange(depth);
    const std::vector<uint32_t> key = binKeys(depth, range, binCount);
    sortByKeyThenHash(numbered.hash, key, binCount, order);
    orderHashCollisionsByGeometry(numbered, key, order);

    const std::vector<uint32_t>& global = numbered.global;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, order.size()), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) order[i] = global[order[i]];
    });

    if (statistics) recordStatistics(range, key, binCount, *statistics);
}

}  // namespace hdhair
