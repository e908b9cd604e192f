#include "hdHair/gl/FragmentListPass.h"

#include <algorithm>

#include "hdHair/gl/GpuMemory.h"
#include "hdHair/gl/RenderTarget.h"
#include "hdHair/gl/StrandPass.h"

namespace hdhair::gl {

namespace {

constexpr GLint kResolveIds = 0;  // uniform location in shaders/fragmentListResolve.frag
// shaders/strandRaster.comp's workgroup size, uniform locations and depth texture unit.
constexpr GLuint kRasterWorkgroup = 32;
constexpr GLint kRasterRangeFirst = 0, kRasterRangeCount = 1;
constexpr GLuint kRasterFrameDepthUnit = 9;
// Segments a dispatch: GL guarantees 65535 workgroups in x.
constexpr uint64_t kRasterDispatchSegments = uint64_t(65535) * kRasterWorkgroup;

// The ranges with neighbours joined: the drawn prims' segments mostly lie
// back to back, and each range costs a dispatch.
std::vector<SegmentRange> joinedRanges(const std::vector<SegmentRange>& ranges) {
    std::vector<SegmentRange> joined;
    for (const SegmentRange& range : ranges) {
        if (range.count == 0) continue;
        if (!joined.empty() && joined.back().first + joined.back().count == range.first)
            joined.back().count += range.count;
        else
            joined.push_back(range);
    }
    return joined;
}

}  // namespace

FragmentListPass::FragmentListPass()
    : listPrograms_({"strand.vert", "strand.tesc", "strand.tese", "strand.geom", "strandFragmentList.frag"}),
      computePrograms_({"strandRaster.comp"}),
      resolveProgram_(createProgram({"fullscreen.vert", "fragmentListResolve.frag"})),
      emptyVertexArray_(createVertexArray()),
      counter_(createBuffer(nullptr, 4 * sizeof(uint32_t), GL_DYNAMIC_STORAGE_BIT | GL_MAP_READ_BIT, "fragmentLists")),
      order_(createBuffer(nullptr, sizeof(uint32_t), 0, "fragmentLists")) {
    checkGlError("setting up exact transparency");
}

void FragmentListPass::rasterizeInCompute(const std::vector<SegmentRange>& ranges, ShadingFeatures features,
                                          GLuint frameDepth) {
    const Program& program = computePrograms_.get(features);
    glUseProgram(program.get());
    glBindTextureUnit(kRasterFrameDepthUnit, frameDepth);
    for (const SegmentRange& range : joinedRanges(ranges)) {
        for (uint64_t first = range.first; first < range.first + range.count; first += kRasterDispatchSegments) {
            const uint64_t count = std::min(range.first + range.count - first, kRasterDispatchSegments);
            glProgramUniform1ui(program.get(), kRasterRangeFirst, GLuint(first));
            glProgramUniform1ui(program.get(), kRasterRangeCount, GLuint(count));
            glDispatchCompute(GLuint((count + kRasterWorkgroup - 1) / kRasterWorkgroup), 1, 1);
        }
    }
    glBindTextureUnit(kRasterFrameDepthUnit, 0);
}

void FragmentListPass::ensureNodes(size_t nodes) {
    if (nodes <= nodeCapacity_ && nodes_) return;
    nodes_ = createBuffer(nullptr, std::max<size_t>(nodes, 1) * kFragmentNodeBytes, 0, "fragmentLists");
    nodeCapacity_ = nodes;
}

uint64_t FragmentListPass::fillLists(const StrandGeometry& geometry, const std::vector<SegmentRange>& ranges,
                                     float maxSegmentsPerSpan, ShadingFeatures features, FragmentSource source,
                                     GLuint frameDepth) {
    const GLuint listEnd = 0xffffffffu;
    glClearTexImage(heads_.get(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &listEnd);
    const uint32_t counter[4] = {0, uint32_t(std::min<size_t>(nodeCapacity_, 0xffffffffu)), 0, 0};
    glNamedBufferSubData(counter_.get(), 0, sizeof counter, counter);

    geometry.bind();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, order_.get());  // declared, unread (no ordering needed)
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, nodes_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, counter_.get());
    glBindImageTexture(0, heads_.get(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    glBindVertexArray(emptyVertexArray_.get());
    if (source == FragmentSource::ComputeRaster) {
        // The compute rasteriser reads the frame's depth itself.
        rasterizeInCompute(ranges, features, frameDepth);
    } else {
        // Opaque geometry's depth rejects hidden fragments; the strands
        // themselves write nothing to the framebuffer.
        glUseProgram(listPrograms_.get(features).get());
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LEQUAL);
        glDepthMask(GL_FALSE);
        glDisable(GL_BLEND);
        glDisable(GL_CULL_FACE);
        // Every draw buffer: the list shader has no outputs, so whatever reached
        // an unmasked attachment would be undefined.
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        geometry.drawPatches(ranges, maxSegmentsPerSpan);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    uint32_t offered = 0;
    glGetNamedBufferSubData(counter_.get(), 0, sizeof offered, &offered);
    return offered;
}

uint64_t FragmentListPass::render(const StrandGeometry& geometry, const std::vector<SegmentRange>& ranges, int width,
                                  int height, size_t capacity, float maxSegmentsPerSpan, bool writeIds,
                                  ShadingFeatures features, FragmentSource source, GLuint frameDepth) {
    if (width != headsWidth_ || height != headsHeight_) {
        GLuint name = 0;
        glCreateTextures(GL_TEXTURE_2D, 1, &name);
        heads_ = Texture(name);
        glTextureStorage2D(heads_.get(), 1, GL_R32UI, width, height);
        recordTextureStorage(heads_.get(), GL_R32UI, width, height, 1, 0, "fragmentLists");
        headsWidth_ = width;
        headsHeight_ = height;
    }
    // The nodes take what the frame needs, not the whole budget: storage is
    // made (and, on llvmpipe, zeroed) when it is allocated, which costs
    // about as much as the list pass itself at a 512 MB budget. A first
    // guess of two fragments a pixel, then what the last frame counted and a
    // quarter more; a frame that finds its guess too small is drawn again
    // into storage of the size it counted (its count is exact).
    const size_t guess = std::max(nodeCapacity_, std::min(capacity, size_t(width) * size_t(height) * 2));
    ensureNodes(guess);
    uint64_t offered = fillLists(geometry, ranges, maxSegmentsPerSpan, features, source, frameDepth);
    if (offered > nodeCapacity_ && offered <= capacity) {
        ensureNodes(std::min<size_t>(capacity, size_t(offered + offered / 4)));
        offered = fillLists(geometry, ranges, maxSegmentsPerSpan, features, source, frameDepth);
    }

    // Pass 2: resolve every pixel over what the frame holds (opaque meshes,
    // or nothing): colour composited (ONE, ONE_MINUS_SRC_ALPHA) and the
    // nearest depth min-blended, then the ids where a listed fragment
    // defines them (integer images cannot blend, so they take a draw of
    // their own that discards elsewhere).
    glUseProgram(resolveProgram_.get());
    glDisable(GL_DEPTH_TEST);
    glProgramUniform1i(resolveProgram_.get(), kResolveIds, 0);
    for (int id = 0; id < 3; ++id) glColorMaski(GLuint(kFirstIdOutput + id), GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glEnablei(GL_BLEND, kColorOutput);
    glBlendEquationi(kColorOutput, GL_FUNC_ADD);
    glBlendFunci(kColorOutput, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glEnablei(GL_BLEND, kNearestDepthOutput);
    glBlendEquationi(kNearestDepthOutput, GL_MIN);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    if (writeIds) {
        glProgramUniform1i(resolveProgram_.get(), kResolveIds, 1);
        glColorMaski(kColorOutput, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glColorMaski(kNearestDepthOutput, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    }
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    uint32_t longLists[2] = {0, 0};
    glGetNamedBufferSubData(counter_.get(), 2 * sizeof(uint32_t), sizeof longLists, longLists);
    overlongPixels_ = longLists[0];
    unwalkedPixels_ = longLists[1];
    glBindVertexArray(0);
    glUseProgram(0);
    checkGlError("rendering fragment lists");
    return offered;
}

}  // namespace hdhair::gl
