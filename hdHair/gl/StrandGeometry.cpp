#include "hdHair/gl/StrandGeometry.h"

#include "hdHair/curves/PreparedCurves.h"

namespace hdhair::gl {

StrandGeometry::StrandGeometry(const std::vector<StrandControlPoint>& controlPoints,
                               const std::vector<int32_t>& segmentCurves, const std::vector<glm::ivec2>& segmentPrims,
                               const std::vector<int32_t>& segmentMaterials)
    : controlPoints_(createBuffer(controlPoints.data(), controlPoints.size() * sizeof(StrandControlPoint))),
      segmentCurves_(createBuffer(segmentCurves.data(), segmentCurves.size() * sizeof(int32_t))),
      segmentPrims_(createBuffer(segmentPrims.data(), segmentPrims.size() * sizeof(glm::ivec2))),
      segmentMaterials_(createBuffer(segmentMaterials.data(), segmentMaterials.size() * sizeof(int32_t))),
      segmentCount_(segmentCurves.size()) {}

void StrandGeometry::bind() const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, controlPoints_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, segmentCurves_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, segmentPrims_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, segmentMaterials_.get());
}

}  // namespace hdhair::gl
