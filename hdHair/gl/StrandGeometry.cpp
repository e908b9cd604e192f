#include "hdHair/gl/StrandGeometry.h"

#include <algorithm>
#include <utility>

#include "hdHair/curves/PreparedCurves.h"

namespace hdhair::gl {

namespace {

constexpr size_t kControlPointBytes = sizeof(StrandControlPoint);
constexpr size_t kFirstControlBytes = sizeof(uint32_t), kCurveBytes = sizeof(int32_t), kSlotBytes = sizeof(int32_t),
                 kDrawnPrimBytes = sizeof(glm::ivec4);

// A buffer of `bytes` holding the first `keep` bytes of `old` (a GPU copy).
Buffer grown(const Buffer& old, size_t keep, size_t bytes) {
    Buffer buffer = createBuffer(nullptr, bytes, GL_DYNAMIC_STORAGE_BIT, "strandGeometry");
    if (old && keep > 0) glCopyNamedBufferSubData(old.get(), buffer.get(), 0, 0, GLsizeiptr(keep));
    return buffer;
}

}  // namespace

StrandGeometry::StrandGeometry() {
    reserve(1, 4);
    writeDrawnPrims({glm::ivec4(0)});
}

void StrandGeometry::reserve(size_t segments, size_t controls) {
    // Half again as much as asked, so that a scene that grows a prim at a
    // time copies O(n) in total.
    if (controls > controlCapacity_) {
        size_t capacity = std::max(controls, controlCapacity_ + controlCapacity_ / 2);
        controlPoints_ = grown(controlPoints_, controlCapacity_ * kControlPointBytes, capacity * kControlPointBytes);
        controlCapacity_ = capacity;
    }
    if (segments <= capacity_) {
        checkGlError("growing the strand buffers");
        return;
    }
    size_t capacity = std::max(segments, capacity_ + capacity_ / 2);
    segmentFirstControls_ =
        grown(segmentFirstControls_, capacity_ * kFirstControlBytes, capacity * kFirstControlBytes);
    segmentCurves_ = grown(segmentCurves_, capacity_ * kCurveBytes, capacity * kCurveBytes);
    segmentSlots_ = grown(segmentSlots_, capacity_ * kSlotBytes, capacity * kSlotBytes);
    capacity_ = capacity;
    checkGlError("growing the strand buffers");
}

void StrandGeometry::write(size_t first, size_t firstControl, const PreparedCurves& curves, uint32_t slot) {
    const size_t count = curves.segmentCount();
    if (count == 0) return;
    glNamedBufferSubData(controlPoints_.get(), GLintptr(firstControl * kControlPointBytes),
                         GLsizeiptr(curves.controlPoints.size() * kControlPointBytes), curves.controlPoints.data());
    std::vector<uint32_t> firstControls(count);
    for (size_t s = 0; s < count; ++s) firstControls[s] = uint32_t(firstControl + curves.segmentFirstControl[s]);
    glNamedBufferSubData(segmentFirstControls_.get(), GLintptr(first * kFirstControlBytes),
                         GLsizeiptr(count * kFirstControlBytes), firstControls.data());
    std::vector<int32_t> curveIndices(curves.segmentCurve.begin(), curves.segmentCurve.end());
    glNamedBufferSubData(segmentCurves_.get(), GLintptr(first * kCurveBytes), GLsizeiptr(count * kCurveBytes),
                         curveIndices.data());
    std::vector<int32_t> slots(count, int32_t(slot));
    glNamedBufferSubData(segmentSlots_.get(), GLintptr(first * kSlotBytes), GLsizeiptr(count * kSlotBytes),
                         slots.data());
}

void StrandGeometry::writeDrawnPrims(const std::vector<glm::ivec4>& slots) {
    if (slots.size() > drawnPrimCapacity_) {
        drawnPrimCapacity_ = std::max(slots.size(), drawnPrimCapacity_ + drawnPrimCapacity_ / 2);
        drawnPrims_ = createBuffer(nullptr, drawnPrimCapacity_ * kDrawnPrimBytes, GL_DYNAMIC_STORAGE_BIT,
                                   "strandGeometry");
    }
    if (!slots.empty())
        glNamedBufferSubData(drawnPrims_.get(), 0, GLsizeiptr(slots.size() * kDrawnPrimBytes), slots.data());
}

void StrandGeometry::bind() const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, controlPoints_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, segmentCurves_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, segmentSlots_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, drawnPrims_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 15, segmentFirstControls_.get());
}

}  // namespace hdhair::gl
