#pragma once
// How the strands' patches are cut into draw calls. One draw a prim range is
// what GL wants, but Mesa 22.3's llvmpipe draws triangles between unrelated
// vertices (long spikes across the image, and far slower frames) once one
// draw's tessellator emits too many vertices (examples/dense_clump.usda broke
// at high tessellation in single draws). Draws of at most 2,048 emitted
// vertices (counted as 2 (level + 1) a patch at the highest level, as when
// the strands were a quad domain; since they are isolines the tessellator
// emits level + 1) render correctly at every level; other drivers get whole
// ranges. The drawBatching setting overrides the choice (tests compare both).
//
// llvmpipe also bins every submitted draw before its threads rasterise it,
// and keeps up to 64 binned scenes of up to 36 MB each: blended strands
// rasterise slower than they bin, so without a pause the queue grows to
// most of a large groom's peak memory. Batched draws therefore wait, every
// kDrawsBetweenFences draws, for the fence set that many draws before
// (docs/performance.md, "Memory", has what that saves).

#include <string>
#include <vector>

#include "hdHair/gl/SegmentRange.h"

namespace hdhair::gl {

struct PatchBatching {
    // Most vertices one draw's tessellator may emit; 0: one draw a range.
    int maxEmittedVertices = 0;
    // Draws between fences when batched: at most twice as many are queued.
    static constexpr int kDrawsBetweenFences = 64;
    std::string reason;  // why, for --verbose

    // Batched, or not, on any driver (drawBatching on or off).
    static PatchBatching forced(bool batched);
    // As the driver needs (drawBatching auto).
    static PatchBatching forDriver(const std::string& glRenderer);
    std::string describe() const;  // "draws of at most 2048 emitted vertices (llvmpipe: ...)"

    // Issues the draws of `ranges` (4 control points a patch; the program,
    // vertex array and state are the caller's). `maxSegmentsPerSpan` bounds
    // the vertices a patch emits.
    void draw(const std::vector<SegmentRange>& ranges, float maxSegmentsPerSpan) const;
};

}  // namespace hdhair::gl
