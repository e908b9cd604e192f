#include "hdHair/gl/StrandGeometry.h"

#include <algorithm>
#include <utility>

#include "hdHair/curves/PreparedCurves.h"

namespace hdhair::gl {

namespace {

constexpr size_t kControlPointBytes = 4 * sizeof(StrandControlPoint);  // per segment
constexpr size_t kCurveBytes = sizeof(int32_t), kPrimBytes = sizeof(glm::ivec2), kMaterialBytes = sizeof(int32_t);

// A buffer of `bytes` holding the first `keep` bytes of `old` (a GPU copy).
Buffer grown(const Buffer& old, size_t keep, size_t bytes) {
    Buffer buffer = createBuffer(nullptr, bytes, GL_DYNAMIC_STORAGE_BIT, "strandGeometry");
    if (old && keep > 0) glCopyNamedBufferSubData(old.get(), buffer.get(), 0, 0, GLsizeiptr(keep));
    return buffer;
}

}  // namespace

StrandGeometry::StrandGeometry() { reserve(1); }

void StrandGeometry::reserve(size_t segments) {
    if (segments <= capacity_) return;
    // Half again as much as asked, so that a scene that grows a prim at a
    // time copies O(n) in total.
    size_t capacity = std::max(segments, capacity_ + capacity_ / 2);
    controlPoints_ = grown(controlPoints_, capacity_ * kControlPointBytes, capacity * kControlPointBytes);
    segmentCurves_ = grown(segmentCurves_, capacity_ * kCurveBytes, capacity * kCurveBytes);
    segmentPrims_ = grown(segmentPrims_, capacity_ * kPrimBytes, capacity * kPrimBytes);
    segmentMaterials_ = grown(segmentMaterials_, capacity_ * kMaterialBytes, capacity * kMaterialBytes);
    capacity_ = capacity;
    checkGlError("growing the strand buffers");
}

void StrandGeometry::write(size_t first, const PreparedCurves& curves, glm::ivec2 primAndInstance, int32_t material) {
    const size_t count = curves.segmentCount();
    if (count == 0) return;
    glNamedBufferSubData(controlPoints_.get(), GLintptr(first * kControlPointBytes), GLsizeiptr(count * kControlPointBytes),
                         curves.controlPoints.data());
    std::vector<int32_t> curveIndices(curves.segmentCurve.begin(), curves.segmentCurve.end());
    glNamedBufferSubData(segmentCurves_.get(), GLintptr(first * kCurveBytes), GLsizeiptr(count * kCurveBytes),
                         curveIndices.data());
    std::vector<glm::ivec2> prims(count, primAndInstance);
    glNamedBufferSubData(segmentPrims_.get(), GLintptr(first * kPrimBytes), GLsizeiptr(count * kPrimBytes),
                         prims.data());
    writeMaterial(first, count, material);
}

void StrandGeometry::writeMaterial(size_t first, size_t count, int32_t material) {
    std::vector<int32_t> materials(count, material);
    glNamedBufferSubData(segmentMaterials_.get(), GLintptr(first * kMaterialBytes), GLsizeiptr(count * kMaterialBytes),
                         materials.data());
}

void StrandGeometry::bind() const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, controlPoints_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, segmentCurves_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, segmentPrims_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, segmentMaterials_.get());
}

}  // namespace hdhair::gl
