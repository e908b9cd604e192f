#pragma once
// The GPU copy of every strand a frame draws, all prims in one set of storage
// buffers so that their segments can be sorted against each other: control
// points (4 a segment, read by strand.vert) and, per segment, its curve index,
// prim id and instance index, and hair material
// (shaders/include/strandGeometry.glsl).
//
// Each prim owns a range of segments (hdHair/render/StrandUploads.h decides
// which): a changed prim rewrites its own range, and nothing else moves.
// Capacity grows by copying on the GPU, so growing never re-sends the rest.

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "hdHair/gl/GlObjects.h"

namespace hdhair {
struct PreparedCurves;
}

namespace hdhair::gl {

class StrandGeometry {
public:
    StrandGeometry();

    size_t capacity() const { return capacity_; }  // in segments
    // Makes room for at least `segments`, keeping what is there.
    void reserve(size_t segments);
    // Writes a prim's segments at [first, first + curves.segmentCount()).
    void write(size_t first, const PreparedCurves& curves, glm::ivec2 primAndInstance, int32_t material);
    // Changes the material of [first, first + count) only.
    void writeMaterial(size_t first, size_t count, int32_t material);
    // Binds the storage buffers at the bindings the shaders use (1 to 3, and 7).
    void bind() const;

private:
    Buffer controlPoints_, segmentCurves_, segmentPrims_, segmentMaterials_;
    size_t capacity_ = 0;
};

}  // namespace hdhair::gl
