#include "hdHair/gl/LightViewSpans.h"

#include <algorithm>
#include <cstring>

namespace hdhair::gl {

namespace {
constexpr GLuint kLevelsWorkgroup = 64;  // lightViewLevels.comp's local_size_x

// Grows `buffer` to hold at least `count` uint32s (contents not kept).
void ensureCapacity(Buffer& buffer, size_t& capacity, size_t count) {
    if (count <= capacity && buffer) return;
    capacity = std::max<size_t>(count, 1);
    buffer = createBuffer(nullptr, capacity * sizeof(uint32_t), GL_DYNAMIC_STORAGE_BIT, "lightViewSpans");
}
}  // namespace

void LightViewSpans::build(const StrandGeometry& geometry, const std::vector<SegmentRange>& ranges,
                           const FrameUniforms& lightView) {
    // Compiled on first use: frames without strand lines never pay for it.
    if (!levelsProgram_) levelsProgram_ = createProgram({"lightViewLevels.comp"});
    size_t total = 0;
    for (const SegmentRange& range : ranges) total += size_t(range.count);
    ensureCapacity(levels_, levelCapacity_, total);
    ensureCapacity(list_, listCapacity_, total);

    geometry.bind();
    glUseProgram(levelsProgram_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, levels_.get());
    // GL guarantees 65,535 workgroups a dispatch: larger ranges go in pieces.
    const uint64_t piece = uint64_t(65535) * kLevelsWorkgroup;
    size_t written = 0;
    for (const SegmentRange& range : ranges)
        for (uint64_t first = range.first; first < range.first + range.count; first += piece) {
            const uint64_t count = std::min(piece, range.first + range.count - first);
            glUniform1ui(0, GLuint(first));
            glUniform1ui(1, GLuint(count));
            glUniform1ui(2, GLuint(written));
            glDispatchCompute(GLuint((count + kLevelsWorkgroup - 1) / kLevelsWorkgroup), 1, 1);
            written += size_t(count);
        }
    glUseProgram(0);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    readLevels_.resize(total);
    if (total > 0) glGetNamedBufferSubData(levels_.get(), 0, GLsizeiptr(total * sizeof(uint32_t)), readLevels_.data());

    listed_.clear();
    listed_.reserve(total);
    for (int pass = 0; pass < 2; ++pass) {  // one-segment spans, then the rest
        size_t index = 0;
        for (const SegmentRange& range : ranges)
            for (uint64_t segment = range.first; segment < range.first + range.count; ++segment, ++index) {
                const uint32_t level = readLevels_[index];
                if (level != 0 && (level == 1) == (pass == 0)) listed_.push_back(uint32_t(segment));
            }
        if (pass == 0) straight_ = listed_.size();
    }
    tessellated_ = listed_.size() - straight_;
    if (!listed_.empty())
        glNamedBufferSubData(list_.get(), 0, GLsizeiptr(listed_.size() * sizeof(uint32_t)), listed_.data());
    checkGlError("listing a light view's spans");

    builtRanges_ = ranges;
    builtView_ = lightView;
    built_ = true;
}

bool LightViewSpans::builtFor(const std::vector<SegmentRange>& ranges, const FrameUniforms& lightView) const {
    return built_ && builtRanges_ == ranges && std::memcmp(&builtView_, &lightView, sizeof(FrameUniforms)) == 0;
}

void LightViewSpans::bindList() const { glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, list_.get()); }

}  // namespace hdhair::gl
