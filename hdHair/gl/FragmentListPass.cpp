#include "hdHair/gl/FragmentListPass.h"

#include <algorithm>

#include "hdHair/gl/GpuMemory.h"
#include "hdHair/gl/RenderTarget.h"
#include "hdHair/gl/StrandPass.h"

namespace hdhair::gl {

namespace {

constexpr GLint kResolveIds = 0;  // uniform location in shaders/fragmentListResolve.frag
constexpr GLint kResolveImageSize = 1;  // shaders/fragmentListTile.vert
constexpr GLint kTilesInImage = 0;  // shaders/fragmentListTiles.comp
constexpr GLuint kTileWorkgroup = 64;
// Without the plan's estimate: thin hair lists about a fragment a span far
// away and about a dozen close up (docs/performance.md, "Where compute
// pays": 1.1 on Ratboy and 11.4 on the bear at 1280 px), without holding two
// fragments a pixel of a mostly empty frame.
constexpr uint64_t kFirstGuessFragmentsPerSpan = 12;
// With it: the TressFX bear at 1280 px lists 1.6 fragments a pixel.
constexpr uint64_t kMostFirstGuessFragmentsPerPixel = 4;
// Storage is never cut below this many fragments (128 KB).
constexpr size_t kFewestNodes = 4096;
// The counter's four words before its tile marks (FragmentCounter in
// shaders/include/fragmentLists.glsl), and the indirect draw's before its
// tiles (shaders/include/resolvedTiles.glsl).
constexpr size_t kCounterHeaderBytes = 4 * sizeof(uint32_t), kTileDrawHeaderBytes = 4 * sizeof(uint32_t);
// shaders/strandRaster.comp's workgroup size, uniform locations and depth texture unit.
constexpr GLuint kRasterWorkgroup = 32;
constexpr GLint kRasterRangeFirst = 0, kRasterRangeCount = 1;
constexpr GLuint kRasterFrameDepthUnit = 9;
// Segments a dispatch: GL guarantees 65535 workgroups in x.
constexpr uint64_t kRasterDispatchSegments = uint64_t(65535) * kRasterWorkgroup;

}  // namespace

FragmentListPass::FragmentListPass()
    : listPrograms_({"strand.vert", "strand.tesc", "strand.tese", "strand.geom", "strandFragmentList.frag"}),
      computePrograms_({"strandRaster.comp"}),
      resolveProgram_(createProgram({"fragmentListTile.vert", "fragmentListResolve.frag"})),
      tileProgram_(createProgram({"fragmentListTiles.comp"})),
      emptyVertexArray_(createVertexArray()),
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

void FragmentListPass::ensureImage(int width, int height) {
    if (width == headsWidth_ && height == headsHeight_) return;
    GLuint name = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &name);
    heads_ = Texture(name);
    glTextureStorage2D(heads_.get(), 1, GL_R32UI, width, height);
    recordTextureStorage(heads_.get(), GL_R32UI, width, height, 1, 0, "fragmentLists");
    headsWidth_ = width;
    headsHeight_ = height;
    const size_t tiles = size_t((width + kFragmentListTile - 1) / kFragmentListTile) *
                         size_t((height + kFragmentListTile - 1) / kFragmentListTile);
    tilesInImage_ = tiles;
    // The marks start clear; fragmentListTiles.comp clears them after each frame.
    counter_ = createBuffer(nullptr, kCounterHeaderBytes + tiles * sizeof(uint32_t),
                            GL_DYNAMIC_STORAGE_BIT | GL_MAP_READ_BIT, "fragmentLists");
    const uint32_t zero = 0;
    glClearNamedBufferData(counter_.get(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    tileDraw_ = createBuffer(nullptr, kTileDrawHeaderBytes + tiles * sizeof(uint32_t),
                             GL_DYNAMIC_STORAGE_BIT | GL_MAP_READ_BIT, "fragmentLists");
}

void FragmentListPass::gatherTiles() {
    const uint32_t command[4] = {6, 0, 0, 0};  // six vertices an instance, no instances yet
    glNamedBufferSubData(tileDraw_.get(), 0, sizeof command, command);
    glUseProgram(tileProgram_.get());
    glProgramUniform1ui(tileProgram_.get(), kTilesInImage, GLuint(tilesInImage_));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, counter_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 9, tileDraw_.get());
    glDispatchCompute(GLuint((tilesInImage_ + kTileWorkgroup - 1) / kTileWorkgroup), 1, 1);
    glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

void FragmentListPass::resizeNodes(size_t nodes) {
    nodes_ = createBuffer(nullptr, std::max<size_t>(nodes, 1) * kFragmentNodeBytes, 0, "fragmentLists");
    nodeCapacity_ = nodes;
}

bool FragmentListPass::stopAfterPiece(const ListFilling& filling) {
    if (filling.pieceSegments == 0) return false;
    glFinish();
    stopped_ = filling.stopRequested && filling.stopRequested();
    return stopped_;
}

bool FragmentListPass::listByHardware(const StrandGeometry& geometry, const std::vector<SegmentRange>& ranges,
                                      float maxSegmentsPerSpan, ShadingFeatures features,
                                      const ListFilling& filling) {
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
    bool stopped = false;
    for (const std::vector<SegmentRange>& piece : piecesOf(ranges, filling.pieceSegments)) {
        geometry.drawPatches(piece, maxSegmentsPerSpan);
        if ((stopped = stopAfterPiece(filling))) break;
    }
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    return !stopped;
}

bool FragmentListPass::listInCompute(const std::vector<SegmentRange>& ranges, ShadingFeatures features,
                                     GLuint frameDepth, const ListFilling& filling) {
    // The compute rasteriser reads the frame's depth itself.
    for (const std::vector<SegmentRange>& piece : piecesOf(ranges, filling.pieceSegments)) {
        rasterizeInCompute(piece, features, frameDepth);
        if (stopAfterPiece(filling)) return false;
    }
    return true;
}

uint64_t FragmentListPass::fillLists(const StrandGeometry& geometry, const ListedSegments& segments,
                                     float maxSegmentsPerSpan, ShadingFeatures features, GLuint frameDepth,
                                     const ListFilling& filling) {
    const GLuint listEnd = 0xffffffffu;
    glClearTexImage(heads_.get(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &listEnd);
    const uint32_t counter[4] = {0, uint32_t(std::min<size_t>(nodeCapacity_, 0xffffffffu)), 0, 0};
    glNamedBufferSubData(counter_.get(), 0, sizeof counter, counter);  // the tile marks stay

    geometry.bind();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, order_.get());  // declared, unread (no ordering needed)
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, nodes_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, counter_.get());
    glBindImageTexture(0, heads_.get(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    glBindVertexArray(emptyVertexArray_.get());
    const bool hardwareListed =
        segments.hardware.empty() || listByHardware(geometry, segments.hardware, maxSegmentsPerSpan, features, filling);
    if (hardwareListed && !segments.compute.empty()) listInCompute(segments.compute, features, frameDepth, filling);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    uint32_t offered = 0;
    glGetNamedBufferSubData(counter_.get(), 0, sizeof offered, &offered);
    return offered;
}

size_t FragmentListPass::wantedNodes(const ListedSegments& segments, int width, int height, size_t capacity,
                                     uint64_t expectedFragments) const {
    // The nodes take what the frame needs, not the whole budget: storage is
    // made (and, on llvmpipe, zeroed) when it is allocated, which costs
    // about as much as the list pass itself at a 512 MB budget. A first
    // guess of the plan's estimate and a quarter more, at most
    // kMostFirstGuessFragmentsPerPixel a pixel (the estimate overstates
    // wide, overlapping strands many times); without one, two fragments a
    // pixel or kFirstGuessFragmentsPerSpan a span, whichever is fewer. Then
    // what the last render listed and a quarter more. A render that finds
    // its storage short is drawn again into storage of the size it counted
    // (its count is exact), which on the TressFX bear at 1280 px (12.9
    // fragments a span) doubled its first frame's list pass; storage over
    // four times what the last render wanted is given back.
    uint64_t spans = 0;
    for (const std::vector<SegmentRange>* ranges : {&segments.hardware, &segments.compute})
        for (const SegmentRange& range : *ranges) spans += range.count;
    const uint64_t pixels = uint64_t(width) * uint64_t(height);
    const size_t firstGuess =
        expectedFragments > 0
            ? size_t(std::min(expectedFragments + expectedFragments / 4, pixels * kMostFirstGuessFragmentsPerPixel))
            : size_t(std::min(pixels * 2, spans * kFirstGuessFragmentsPerSpan));
    return std::max(kFewestNodes, std::min(capacity, listedLast_ ? listedLast_ + listedLast_ / 4 : firstGuess));
}

void FragmentListPass::resolveTiles(int width, int height, bool writeIds) {
    // Pass 2: resolve every pixel of the tiles holding fragments over what
    // the frame holds (opaque meshes, or nothing; pixels elsewhere keep
    // it): colour composited (ONE, ONE_MINUS_SRC_ALPHA) and the nearest
    // depth min-blended, then the ids where a listed fragment defines them
    // (integer images cannot blend, so they take a draw of their own that
    // discards elsewhere).
    glUseProgram(resolveProgram_.get());
    glDisable(GL_DEPTH_TEST);
    glProgramUniform1i(resolveProgram_.get(), kResolveIds, 0);
    glProgramUniform2i(resolveProgram_.get(), kResolveImageSize, width, height);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, counter_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 9, tileDraw_.get());
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, tileDraw_.get());
    for (int id = 0; id < 3; ++id) glColorMaski(GLuint(kFirstIdOutput + id), GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glEnablei(GL_BLEND, kColorOutput);
    glBlendEquationi(kColorOutput, GL_FUNC_ADD);
    glBlendFunci(kColorOutput, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glEnablei(GL_BLEND, kNearestDepthOutput);
    glBlendEquationi(kNearestDepthOutput, GL_MIN);
    glDrawArraysIndirect(GL_TRIANGLES, nullptr);
    glDisable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    if (writeIds) {
        glProgramUniform1i(resolveProgram_.get(), kResolveIds, 1);
        glColorMaski(kColorOutput, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glColorMaski(kNearestDepthOutput, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glDrawArraysIndirect(GL_TRIANGLES, nullptr);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    }
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
}

void FragmentListPass::readResolveCounts() {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    uint32_t longLists[2] = {0, 0};
    glGetNamedBufferSubData(counter_.get(), 2 * sizeof(uint32_t), sizeof longLists, longLists);
    overlongPixels_ = longLists[0];
    unwalkedPixels_ = longLists[1];
    uint32_t tiles = 0;
    glGetNamedBufferSubData(tileDraw_.get(), sizeof(uint32_t), sizeof tiles, &tiles);
    resolvedTiles_ = tiles;
}

uint64_t FragmentListPass::render(const StrandGeometry& geometry, const ListedSegments& segments, int width,
                                  int height, size_t capacity, uint64_t expectedFragments, float maxSegmentsPerSpan, bool writeIds,
                                  ShadingFeatures features, GLuint frameDepth, const ListFilling& filling) {
    stopped_ = false;
    ensureImage(width, height);
    const size_t wanted = wantedNodes(segments, width, height, capacity, expectedFragments);
    if (!nodes_ || nodeCapacity_ < wanted || nodeCapacity_ / 4 > wanted) resizeNodes(wanted);
    uint64_t offered = fillLists(geometry, segments, maxSegmentsPerSpan, features, frameDepth, filling);
    if (!stopped_ && offered > nodeCapacity_ && offered <= capacity) {
        resizeNodes(std::min<size_t>(capacity, size_t(offered + offered / 4)));
        offered = fillLists(geometry, segments, maxSegmentsPerSpan, features, frameDepth, filling);
    }
    if (!stopped_) listedLast_ = size_t(std::min<uint64_t>(offered, capacity));
    if (stopped_) {
        // The marks of the tiles listed so far must not reach the next frame.
        gatherTiles();
        glEnable(GL_DEPTH_TEST);
        glDepthMask(GL_TRUE);
        glBindVertexArray(0);
        glUseProgram(0);
        return offered;
    }

    gatherTiles();
    resolveTiles(width, height, writeIds);
    readResolveCounts();
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    glBindVertexArray(0);
    glUseProgram(0);
    checkGlError("rendering fragment lists");
    return offered;
}

}  // namespace hdhair::gl
