// binSortSegments (hdHair/render/BinSort.h): depth bins far to near by each
// segment's farther end point, a geometry hash within a bin, stable for
// identical segments, and correct for any count.

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "hdHair/render/BinSort.h"
#include "hdHair/render/CountingSort.h"

using namespace hdhair;

namespace {

// The camera at the origin looking down -Z: a point's depth is -z.
const glm::dvec3 kCamera(0.0);
const glm::dvec3 kForward(0.0, 0.0, -1.0);

struct Segment {
    glm::vec3 a, b;  // the span's end points (its 2nd and 3rd control points)
};

// Four control points a segment; only the span's end points count for depth.
// Each segment a curve of its own, four controls a span.
PreparedCurves curvesOf(const std::vector<Segment>& segments) {
    PreparedCurves curves;
    for (const Segment& s : segments) {
        StrandControlPoint a{s.a, 0.1f, glm::vec3(0.5f), 1.0f}, b{s.b, 0.1f, glm::vec3(0.5f), 1.0f};
        StrandControlPoint before = a, after = b;
        before.position = 2.0f * s.a - s.b;  // outer controls far away must not matter
        after.position = 2.0f * s.b - s.a + glm::vec3(0.0f, 0.0f, -1000.0f);
        curves.segmentFirstControl.push_back(uint32_t(curves.controlPoints.size()));
        curves.segmentCurve.push_back(uint32_t(curves.segmentCurve.size()));
        curves.controlPoints.insert(curves.controlPoints.end(), {before, a, b, after});
    }
    return curves;
}

// As BinSort keeps it: the farther end point's depth, stored as a float.
double farDepth(const Segment& s) {
    return double(float(
        std::max(glm::dot(glm::dvec3(s.a) - kCamera, kForward), glm::dot(glm::dvec3(s.b) - kCamera, kForward))));
}

std::vector<uint32_t> sortSegments(const std::vector<Segment>& segments, uint32_t bins,
                                   BinSortStatistics* statistics = nullptr) {
    std::vector<uint32_t> order;
    binSortSegments(curvesOf(segments), kCamera, kForward, bins, order, statistics);
    return order;
}

// The bin a segment falls in by BinSort.h's rule, 0 nearest.
uint32_t binOf(const Segment& s, double nearDepth, double farDepthOfAll, uint32_t bins) {
    double t = (farDepth(s) - nearDepth) / (farDepthOfAll - nearDepth);
    return std::min(uint32_t(t * bins), bins - 1);
}

std::vector<Segment> randomSegments(size_t count, unsigned seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> spread(-10.0f, 10.0f), depth(1.0f, 100.0f);
    std::vector<Segment> segments(count);
    for (Segment& s : segments) {
        float z = -depth(random);
        s.a = {spread(random), spread(random), z};
        s.b = s.a + glm::vec3(spread(random), spread(random), spread(random)) * 0.1f;
    }
    return segments;
}

}  // namespace

TEST(BinSort, SegmentsMoreThanABinApartComeFarToNear) {
    // Depths 1..100 in a shuffled order, 1000 bins: each alone in its bin.
    std::vector<Segment> segments;
    for (int i = 0; i < 100; ++i)
        segments.push_back({{0.0f, float(i), -1.0f - float(i)}, {1.0f, float(i), -1.0f - float(i)}});
    std::shuffle(segments.begin(), segments.end(), std::mt19937(5));
    std::vector<uint32_t> order = sortSegments(segments, 1000);
    ASSERT_EQ(order.size(), segments.size());
    for (size_t k = 1; k < order.size(); ++k)
        EXPECT_GT(farDepth(segments[order[k - 1]]), farDepth(segments[order[k]])) << "position " << k;
}

TEST(BinSort, ASegmentIsBinnedByItsFartherEndPoint) {
    // The first segment reaches nearer than the second but also farther: it
    // is drawn first (far to near), whichever end it was authored from.
    for (bool reversed : {false, true}) {
        Segment crossing{{0.0f, 0.0f, -1.0f}, {0.0f, 1.0f, -50.0f}};
        if (reversed) std::swap(crossing.a, crossing.b);
        std::vector<Segment> segments = {{{1.0f, 0.0f, -20.0f}, {1.0f, 1.0f, -20.0f}}, crossing,
                                         {{2.0f, 0.0f, -10.0f}, {2.0f, 1.0f, -10.0f}}};
        EXPECT_EQ(sortSegments(segments, 64), (std::vector<uint32_t>{1, 0, 2})) << (reversed ? "reversed" : "");
    }
}

TEST(BinSort, BinsGroupSegmentsFarToNearAndReportTheirRange) {
    std::vector<Segment> segments = randomSegments(5000, 7);
    for (uint32_t bins : {1u, 4u, 16u, 256u}) {
        BinSortStatistics statistics;
        std::vector<uint32_t> order = sortSegments(segments, bins, &statistics);
        double nearest = INFINITY, farthest = -INFINITY;
        for (const Segment& s : segments) {
            nearest = std::min(nearest, farDepth(s));
            farthest = std::max(farthest, farDepth(s));
        }
        EXPECT_EQ(statistics.nearDepth, nearest);
        EXPECT_EQ(statistics.farDepth, farthest);
        std::vector<bool> occupied(bins, false);
        uint32_t previous = bins - 1;
        for (size_t k = 0; k < order.size(); ++k) {
            uint32_t bin = binOf(segments[order[k]], nearest, farthest, bins);
            occupied[bin] = true;
            ASSERT_LE(bin, previous) << bins << " bins: position " << k << " is in a farther bin than the one before";
            previous = bin;
        }
        EXPECT_EQ(statistics.occupiedBins, uint32_t(std::count(occupied.begin(), occupied.end(), true))) << bins;
    }
    // One bin sorts nothing by depth: the order is the hash's alone, so it
    // differs from both depth order and input order.
    std::vector<uint32_t> oneBin = sortSegments(segments, 1);
    std::vector<uint32_t> identity(segments.size());
    std::iota(identity.begin(), identity.end(), 0u);
    EXPECT_NE(oneBin, identity);
    EXPECT_NE(oneBin, sortSegments(segments, 4096));
}

TEST(BinSort, OrderWithinABinFollowsGeometryNotInputOrder) {
    // Shuffled input gives the same segments in the same order: Hydra may
    // sync prims in any order, and the picture must not change.
    std::vector<Segment> segments = randomSegments(2000, 11);
    std::vector<uint32_t> permutation(segments.size());
    std::iota(permutation.begin(), permutation.end(), 0u);
    std::shuffle(permutation.begin(), permutation.end(), std::mt19937(3));
    std::vector<Segment> shuffled;
    for (uint32_t i : permutation) shuffled.push_back(segments[i]);
    for (uint32_t bins : {1u, 16u}) {
        std::vector<uint32_t> original = sortSegments(segments, bins), reordered = sortSegments(shuffled, bins);
        ASSERT_EQ(original.size(), reordered.size());
        for (size_t k = 0; k < original.size(); ++k)
            ASSERT_EQ(original[k], permutation[reordered[k]]) << bins << " bins, position " << k;
    }
}

TEST(BinSort, IdenticalSegmentsKeepTheirInputOrder) {
    // Equal geometry hashes alike: the counting sorts are stable, so copies
    // stay in the order they came in, among other segments in their bin.
    Segment copy{{0.5f, 0.5f, -5.0f}, {0.7f, 0.2f, -5.5f}};
    std::vector<Segment> segments = randomSegments(300, 13);
    std::vector<uint32_t> copies = {17, 60, 61, 250};
    for (uint32_t index : copies) segments[index] = copy;
    for (uint32_t bins : {1u, 8u}) {
        std::vector<uint32_t> order = sortSegments(segments, bins);
        std::vector<uint32_t> seen;
        for (uint32_t index : order)
            if (std::find(copies.begin(), copies.end(), index) != copies.end()) seen.push_back(index);
        EXPECT_EQ(seen, copies) << bins << " bins";
    }
}

TEST(BinSort, LargeCountsGiveAPermutationInBinOrder) {
    // More segments than the 65,536 hash buckets, sorted in parallel.
    const size_t count = 300000;
    std::vector<Segment> segments = randomSegments(count, 17);
    BinSortStatistics statistics;
    std::vector<uint32_t> order = sortSegments(segments, 1024, &statistics);
    ASSERT_EQ(order.size(), count);
    std::vector<bool> seen(count, false);
    uint32_t previous = 1023;
    for (size_t k = 0; k < count; ++k) {
        ASSERT_LT(order[k], count);
        ASSERT_FALSE(seen[order[k]]) << "segment " << order[k] << " twice";
        seen[order[k]] = true;
        uint32_t bin = binOf(segments[order[k]], statistics.nearDepth, statistics.farDepth, 1024);
        ASSERT_LE(bin, previous) << "position " << k;
        previous = bin;
    }
    EXPECT_EQ(statistics.occupiedBins, 1024u) << "depths 1..100 over 300,000 segments fill every bin";
}

TEST(BinSort, NoSegmentsAndOneDepthAreHandled) {
    BinSortStatistics statistics;
    statistics.occupiedBins = 99;
    EXPECT_TRUE(sortSegments({}, 256, &statistics).empty());
    EXPECT_EQ(statistics.occupiedBins, 0u);
    // Every segment at one depth: one bin, in hash order, each once.
    std::vector<Segment> flat;
    for (int i = 0; i < 50; ++i) flat.push_back({{float(i), 0.0f, -3.0f}, {float(i), 1.0f, -3.0f}});
    std::vector<uint32_t> order = sortSegments(flat, 256, &statistics);
    std::vector<uint32_t> sorted = order;
    std::sort(sorted.begin(), sorted.end());
    std::vector<uint32_t> identity(flat.size());
    std::iota(identity.begin(), identity.end(), 0u);
    EXPECT_EQ(sorted, identity);
    EXPECT_EQ(statistics.occupiedBins, 1u);
    // Zero bins are taken as one.
    EXPECT_EQ(sortSegments(flat, 0), sortSegments(flat, 1));
}

// Spans that share their curve's controls (PreparedCurves) sort exactly as
// the same spans with four controls each: the sort reads each span's own.
TEST(BinSort, SharedControlsSortAsFourControlsASpan) {
    PreparedCurves shared, unshared;
    for (int curve = 0; curve < 3; ++curve) {
        const uint32_t first = uint32_t(shared.controlPoints.size());
        for (int k = 0; k < 9; ++k) {
            const float t = float(k);
            shared.controlPoints.push_back(StrandControlPoint{
                glm::vec3(0.3f * curve + std::sin(t), 0.2f * t, -2.0f - std::cos(1.7f * t + curve)), 0.1f,
                glm::vec3(0.5f), 1.0f});
        }
        for (uint32_t s = 0; s < 6; ++s) {
            shared.segmentFirstControl.push_back(first + s);
            shared.segmentCurve.push_back(uint32_t(curve));
        }
    }
    for (size_t s = 0; s < shared.segmentCount(); ++s) {
        unshared.segmentFirstControl.push_back(uint32_t(unshared.controlPoints.size()));
        unshared.segmentCurve.push_back(shared.segmentCurve[s]);
        unshared.controlPoints.insert(unshared.controlPoints.end(), shared.spanControls(s), shared.spanControls(s) + 4);
    }
    std::vector<uint32_t> sharedOrder, unsharedOrder;
    binSortSegments(shared, kCamera, kForward, 4, sharedOrder);
    binSortSegments(unshared, kCamera, kForward, 4, unsharedOrder);
    EXPECT_EQ(sharedOrder, unsharedOrder);
    // Read as four controls a span, the shared ones give another order.
    PreparedCurves misread = shared;
    for (size_t s = 0; s < misread.segmentCount(); ++s) misread.segmentFirstControl[s] = uint32_t(std::min(4 * s, size_t(23)));
    std::vector<uint32_t> misreadOrder;
    binSortSegments(misread, kCamera, kForward, 4, misreadOrder);
    EXPECT_NE(misreadOrder, sharedOrder);
}

TEST(CountingSort, EveryBlockCountGivesTheSerialStableOrder) {
    // Few keys (long runs, where stability shows) and many (hash buckets),
    // block counts that do and do not divide the input, more blocks than
    // elements, and the automatic choice.
    std::mt19937 random(3);
    for (uint32_t keyCount : {3u, 65536u}) {
        for (size_t n : {size_t(0), size_t(1), size_t(17), size_t(100000)}) {
            std::vector<uint32_t> key(n), in(n);
            std::uniform_int_distribution<uint32_t> pick(0, keyCount - 1);
            for (uint32_t& k : key) k = pick(random);
            std::iota(in.begin(), in.end(), 0u);
            std::shuffle(in.begin(), in.end(), random);
            std::vector<uint32_t> expected = in;
            std::stable_sort(expected.begin(), expected.end(), [&](uint32_t a, uint32_t b) { return key[a] < key[b]; });
            for (size_t blocks : {size_t(0), size_t(1), size_t(2), size_t(7), size_t(64), size_t(1000)}) {
                std::vector<uint32_t> out;
                stableCountingSort(in, key, keyCount, out, blocks);
                EXPECT_EQ(out, expected) << "keys " << keyCount << ", n " << n << ", blocks " << blocks;
            }
        }
    }
}
