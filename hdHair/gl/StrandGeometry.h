#pragma once
// The GPU copy of every strand a frame draws, all prims in one set of storage
// buffers so that their segments can be sorted against each other: control
// points (each curve's, shared by its spans where PreparedCurves shares them,
// read by strand.vert) and, per segment, where its four controls start, its
// curve index and its prim's slot in a small table of the drawn prims' ids
// and hair materials (shaders/include/strandGeometry.glsl): a prim's material
// changes one table entry, not a value per segment.
//
// Each prim owns a range of segments and one of control points
// (hdHair/render/StrandUploads.h decides which): a changed prim rewrites its
// own ranges, and nothing else moves.
// Capacity grows by copying on the GPU, so growing never re-sends the rest.

#include <cstdint>
#include <utility>
#include <vector>

#include <glm/vec4.hpp>

#include "hdHair/gl/GlObjects.h"
#include "hdHair/gl/PatchBatching.h"
#include "hdHair/gl/SegmentRange.h"

namespace hdhair {
struct PreparedCurves;
}

namespace hdhair::gl {

class StrandGeometry {
public:
    StrandGeometry();

    size_t capacity() const { return capacity_; }  // in segments
    size_t controlCapacity() const { return controlCapacity_; }
    // Makes room for at least `segments` and `controls`, keeping what is there.
    void reserve(size_t segments, size_t controls);
    // Writes a prim's segments at [first, first + curves.segmentCount()),
    // its control points from `firstControl` on, and its table slot.
    void write(size_t first, size_t firstControl, const PreparedCurves& curves, uint32_t slot);
    // The drawn prims' table, by slot: (primId, instanceId, material, 0).
    void writeDrawnPrims(const std::vector<glm::ivec4>& slots);
    // Binds the storage buffers at the bindings the shaders use (1 to 3, 7 and 15).
    void bind() const;

    // How draws of these patches are cut for the driver (PatchBatching.h).
    void setBatching(PatchBatching batching) { batching_ = std::move(batching); }
    const PatchBatching& batching() const { return batching_; }
    // Issues the draws of `ranges`, one patch a segment (the program, vertex
    // array and state are the caller's, the buffers bound).
    void drawPatches(const std::vector<SegmentRange>& ranges, float maxSegmentsPerSpan) const {
        batching_.draw(ranges, maxSegmentsPerSpan);
    }

private:
    Buffer controlPoints_, segmentFirstControls_, segmentCurves_, segmentSlots_, drawnPrims_;
    size_t capacity_ = 0, controlCapacity_ = 0, drawnPrimCapacity_ = 0;
    PatchBatching batching_;
};

}  // namespace hdhair::gl
