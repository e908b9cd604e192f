#pragma once
// The GPU copy of every strand a frame draws, all prims together so that
// their segments can be sorted against each other: control points (4 a
// segment, read by strand.vert) and, per segment, its curve index, prim id
// and instance index, and hair material (shaders/include/strandGeometry.glsl).

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "hdHair/gl/GlObjects.h"

namespace hdhair {
struct StrandControlPoint;
}

namespace hdhair::gl {

class StrandGeometry {
public:
    StrandGeometry(const std::vector<StrandControlPoint>& controlPoints, const std::vector<int32_t>& segmentCurves,
                   const std::vector<glm::ivec2>& segmentPrims, const std::vector<int32_t>& segmentMaterials);

    size_t segmentCount() const { return segmentCount_; }
    // Binds the storage buffers at the bindings the shaders use (1 to 3, and 7).
    void bind() const;

private:
    Buffer controlPoints_, segmentCurves_, segmentPrims_, segmentMaterials_;
    size_t segmentCount_ = 0;
};

}  // namespace hdhair::gl
