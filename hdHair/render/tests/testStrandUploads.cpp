// StrandUploads sends only what changed: each drawn prim keeps its GPU range
// while it is unchanged, rewrites it in place when it changes size-for-size,
// moves to the end when it grows or shrinks, and holes are packed away once
// they outweigh the live segments.

#include <gtest/gtest.h>

#include "hdHair/render/StrandUploads.h"

using namespace hdhair;

namespace {

// One curve of `segments` spans sharing their controls (segments + 3), or
// with four controls each.
std::shared_ptr<const PreparedCurves> curvesOf(size_t segments, bool shared = true) {
    auto curves = std::make_shared<PreparedCurves>();
    curves->segmentCurve.assign(segments, 0);
    curves->controlPoints.resize(shared ? segments + 3 : 4 * segments);
    for (size_t s = 0; s < segments; ++s) curves->segmentFirstControl.push_back(uint32_t(shared ? s : 4 * s));
    return curves;
}

DrawnPrim drawn(const std::string& path, std::shared_ptr<const PreparedCurves> curves, int material = 0) {
    return DrawnPrim{path, std::move(curves), glm::ivec2(1, 0), material};
}

}  // namespace

TEST(StrandUploads, AnUnchangedFrameSendsNothing) {
    StrandUploads uploads;
    auto a = curvesOf(10), b = curvesOf(20);
    StrandUploadPlan first = uploads.update({drawn("/a", a), drawn("/b", b)});
    EXPECT_EQ(first.writtenSegments, 30u);
    ASSERT_EQ(first.writes.size(), 2u);
    EXPECT_EQ(first.ranges[0], (gl::SegmentRange{0, 10}));
    EXPECT_EQ(first.ranges[1], (gl::SegmentRange{10, 20}));
    EXPECT_EQ(first.firstControls, (std::vector<uint64_t>{0, 13}));
    EXPECT_EQ(first.controlCapacityNeeded, 13u + 23u);
    EXPECT_EQ(first.drawRanges.size(), 1u);  // adjacent: one draw range

    StrandUploadPlan second = uploads.update({drawn("/a", a), drawn("/b", b)});
    EXPECT_TRUE(second.writes.empty());
    EXPECT_EQ(second.writtenSegments, 0u);
    EXPECT_EQ(second.ranges, first.ranges);
}

TEST(StrandUploads, AMaterialChangeRewritesOnlyMaterials) {
    StrandUploads uploads;
    auto a = curvesOf(10);
    uploads.update({drawn("/a", a, 0)});
    StrandUploadPlan plan = uploads.update({drawn("/a", a, 3)});
    ASSERT_EQ(plan.writes.size(), 1u);
    EXPECT_TRUE(plan.writes[0].materialOnly);
    EXPECT_EQ(plan.writtenSegments, 0u);
}

TEST(StrandUploads, AChangedPrimRewritesItsOwnRangeOrMovesToTheEnd) {
    StrandUploads uploads;
    auto a = curvesOf(10), b = curvesOf(20);
    uploads.update({drawn("/a", a), drawn("/b", b)});

    // Same size: in place, nothing else sent.
    StrandUploadPlan same = uploads.update({drawn("/a", curvesOf(10)), drawn("/b", b)});
    ASSERT_EQ(same.writes.size(), 1u);
    EXPECT_EQ(same.writes[0].prim, 0u);
    EXPECT_EQ(same.ranges[0], (gl::SegmentRange{0, 10}));
    EXPECT_EQ(same.writtenSegments, 10u);

    // Grown: a new range at the end, the old one a hole; b stays.
    StrandUploadPlan grown = uploads.update({drawn("/a", curvesOf(15)), drawn("/b", b)});
    EXPECT_EQ(grown.ranges[0], (gl::SegmentRange{30, 15}));
    EXPECT_EQ(grown.ranges[1], (gl::SegmentRange{10, 20}));
    EXPECT_EQ(grown.writtenSegments, 15u);
    EXPECT_EQ(grown.holeSegments, 10u);
    EXPECT_EQ(grown.capacityNeeded, 45u);
    // Draw order follows the drawn prims, not the GPU layout.
    ASSERT_EQ(grown.drawRanges.size(), 2u);
    EXPECT_EQ(grown.drawRanges[0], (gl::SegmentRange{30, 15}));
    EXPECT_EQ(grown.drawRanges[1], (gl::SegmentRange{10, 20}));
}

TEST(StrandUploads, RemovedPrimsLeaveHolesUntilTheyOutweighTheLiveSegments) {
    StrandUploads uploads;
    auto big = curvesOf(100000), small = curvesOf(1000);
    uploads.update({drawn("/big", big), drawn("/small", small)});
    // Dropping /big leaves 100,000 free segments against 1,000 live: packed.
    StrandUploadPlan packed = uploads.update({drawn("/small", small)});
    EXPECT_TRUE(packed.repacked);
    EXPECT_EQ(packed.ranges[0], (gl::SegmentRange{0, 1000}));
    EXPECT_EQ(packed.firstControls[0], 0u);  // its controls are packed too
    EXPECT_EQ(packed.controlCapacityNeeded, 1003u);
    EXPECT_EQ(packed.writtenSegments, 1000u);
    EXPECT_EQ(packed.holeSegments, 0u);

    // A small hole is cheaper to keep than a full upload.
    StrandUploads other;
    auto a = curvesOf(1000), b = curvesOf(1000);
    other.update({drawn("/a", a), drawn("/b", b)});
    StrandUploadPlan kept = other.update({drawn("/b", b)});
    EXPECT_FALSE(kept.repacked);
    EXPECT_TRUE(kept.writes.empty());
    EXPECT_EQ(kept.holeSegments, 1000u);
    EXPECT_EQ(kept.ranges[0], (gl::SegmentRange{1000, 1000}));
}

TEST(StrandUploads, NewIdsRewriteThePrim) {
    StrandUploads uploads;
    auto a = curvesOf(4);
    uploads.update({drawn("/a", a)});
    DrawnPrim renumbered = drawn("/a", a);
    renumbered.primAndInstance = glm::ivec2(7, 2);
    StrandUploadPlan plan = uploads.update({renumbered});
    ASSERT_EQ(plan.writes.size(), 1u);
    EXPECT_FALSE(plan.writes[0].materialOnly);
    EXPECT_EQ(plan.ranges[0], (gl::SegmentRange{0, 4}));
}

// Control points are allocated beside the segments: a prim whose segment
// count stays but whose control count changes (its spans stopped sharing)
// must move, or it would write over its neighbour's controls.
TEST(StrandUploads, ControlPointsMoveWithTheirPrimWhenTheirCountChanges) {
    StrandUploads uploads;
    auto a = curvesOf(10), b = curvesOf(20);
    StrandUploadPlan first = uploads.update({drawn("/a", a), drawn("/b", b)});
    ASSERT_EQ(first.firstControls, (std::vector<uint64_t>{0, 13}));
    auto unsharedA = curvesOf(10, false);  // same 10 segments, 40 controls
    StrandUploadPlan second = uploads.update({drawn("/a", unsharedA), drawn("/b", b)});
    ASSERT_EQ(second.writes.size(), 1u);
    EXPECT_EQ(second.ranges[0], (gl::SegmentRange{30, 10}));
    EXPECT_EQ(second.firstControls[0], 36u);  // after /b's 13 .. 36
    EXPECT_EQ(second.firstControls[1], 13u);  // /b stays
    EXPECT_EQ(second.controlCapacityNeeded, 76u);
    // The same counts again: rewritten in place.
    StrandUploadPlan third = uploads.update({drawn("/a", curvesOf(10, false)), drawn("/b", b)});
    EXPECT_EQ(third.firstControls, second.firstControls);
    EXPECT_EQ(third.controlCapacityNeeded, 76u);
}

// Each resident prim keeps one slot in the drawn prims' table; a removed
// prim's slot goes to the next new one, so the table stays as small as the
// most prims drawn at once.
TEST(StrandUploads, SlotsAreKeptAndReused) {
    StrandUploads uploads;
    auto a = curvesOf(4), b = curvesOf(5), c = curvesOf(6);
    StrandUploadPlan first = uploads.update({drawn("/a", a), drawn("/b", b)});
    EXPECT_EQ(first.slots, (std::vector<uint32_t>{0, 1}));
    EXPECT_EQ(first.slotCount, 2u);
    StrandUploadPlan recoloured = uploads.update({drawn("/b", b, 3), drawn("/a", a)});
    EXPECT_EQ(recoloured.slots, (std::vector<uint32_t>{1, 0}));  // drawn order changed, slots did not
    ASSERT_EQ(recoloured.writes.size(), 1u);
    EXPECT_TRUE(recoloured.writes[0].materialOnly);
    StrandUploadPlan replaced = uploads.update({drawn("/c", c), drawn("/b", b, 3)});
    EXPECT_EQ(replaced.slots, (std::vector<uint32_t>{0, 1}));  // /c takes /a's slot
    EXPECT_EQ(replaced.slotCount, 2u);
}
