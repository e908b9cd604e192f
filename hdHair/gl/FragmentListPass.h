#pragma once
// Per-pixel fragment lists: every strand fragment goes into its pixel's
// linked list in a storage buffer (pass 1), then each pixel sorts its list by
// depth and composites it exactly (pass 2). Pass 1 is the hardware
// rasteriser running strandFragmentList.frag (exact transparency: the ground
// truth that bin sorting is measured against), the compute rasteriser,
// strandRaster.comp (strandRaster=compute: thin strands on every core), or
// both, each for its own prims (strandRaster=auto with wide prims). The
// lists' memory is bounded; a frame that needs more reports how much, and the
// renderer falls back.

#include <cstdint>
#include <functional>
#include <vector>

#include "hdHair/gl/GlObjects.h"
#include "hdHair/gl/SegmentRange.h"
#include "hdHair/gl/ShadingPrograms.h"
#include "hdHair/gl/StrandGeometry.h"

namespace hdhair::gl {

constexpr size_t kFragmentNodeBytes = 32;  // FragmentNode in shaders/include/fragmentLists.glsl
// The resolve covers only the square tiles of this many pixels a side that
// hold fragments: HDHAIR_LIST_TILE in shaders/include/fragmentLists.glsl.
constexpr int kFragmentListTile = 16;

// The segments pass 1 lists, by who rasterises them; both fill the same
// lists, which one resolve composites.
struct ListedSegments {
    std::vector<SegmentRange> hardware;  // the strand program's tessellation and rasteriser
    std::vector<SegmentRange> compute;   // strandRaster.comp
};

// How pass 1 runs: in pieces of `pieceSegments` segments (0: all at once),
// each finished before `stopRequested` is asked, so that a frame can stop
// within a fraction of the pass (llvmpipe works only when work is flushed).
struct ListFilling {
    size_t pieceSegments = 0;
    std::function<bool()> stopRequested;
};

class FragmentListPass {
public:
    FragmentListPass();  // compiles the resolve program; list programs as render() asks for them

    // Renders into the currently bound framebuffer, over what it holds: the
    // strands' colour is composited over it, their nearest depth min-blended
    // with it, and their ids (with `writeIds`, when the target has ids)
    // written where a strand fragment defines them; the depth buffer is
    // tested, not written, so opaque geometry drawn before hides what is
    // behind it. The frame and light uniform blocks must be bound
    // (StrandPass::setUniforms). Depth and ids follow
    // hdHair/plan/NearestStrandRule.h.
    // Returns how many fragments the strands produced; more than
    // `capacity` (the budget) means the image is incomplete and must not be
    // used. Storage follows what frames need (the last render's count),
    // up to `capacity`; the first render's storage follows
    // `expectedFragments` (the plan's estimate; 0: unknown).
    // `segments`: the drawn prims' segments, by who lists them. `features`:
    // the shading the list programs compile, as for StrandPass::setUniforms.
    // `frameDepth`: the bound framebuffer's depth texture (single-sampled),
    // which the compute rasteriser tests against as the hardware's depth
    // test would.
    // `filling`: a stop it reports leaves the frame's images as they were
    // (stopped() is then true, and the count returned is not the frame's).
    uint64_t render(const StrandGeometry& geometry, const ListedSegments& segments, int width, int height,
                    size_t capacity, uint64_t expectedFragments, float maxSegmentsPerSpan, bool writeIds,
                    ShadingFeatures features, GLuint frameDepth = 0, const ListFilling& filling = {});
    // The last render() stopped while filling its lists.
    bool stopped() const { return stopped_; }

    // Pixels of the last render() whose lists were too long to sort whole
    // (more than 180 fragments, shaders/fragmentListResolve.frag): composited
    // exactly for their nearest 64 and as one averaged layer behind them;
    // and those of them too long to walk whole within llvmpipe's loop limit.
    uint64_t overlongPixels() const { return overlongPixels_; }
    uint64_t unwalkedPixels() const { return unwalkedPixels_; }
    // The tiles (kFragmentListTile pixels a side) the last render() resolved:
    // those holding fragments, of tilesInImage().
    uint64_t resolvedTiles() const { return resolvedTiles_; }
    uint64_t tilesInImage() const { return tilesInImage_; }

private:
    // Node storage for `nodes` fragments, made anew.
    void resizeNodes(size_t nodes);
    // Pass 1 into storage as it is, hardware then compute; returns the
    // fragments offered (also those past the storage).
    // Sets stopped_ when `filling` stops it.
    uint64_t fillLists(const StrandGeometry& geometry, const ListedSegments& segments, float maxSegmentsPerSpan,
                       ShadingFeatures features, GLuint frameDepth, const ListFilling& filling);
    // Lists `ranges` by the hardware rasteriser, in pieces as `filling` says;
    // false when it stopped.
    bool listByHardware(const StrandGeometry& geometry, const std::vector<SegmentRange>& ranges,
                        float maxSegmentsPerSpan, ShadingFeatures features, const ListFilling& filling);
    bool listInCompute(const std::vector<SegmentRange>& ranges, ShadingFeatures features, GLuint frameDepth,
                       const ListFilling& filling);
    // After a piece of `filling`: waits for it and asks whether to stop.
    bool stopAfterPiece(const ListFilling& filling);
    void rasterizeInCompute(const std::vector<SegmentRange>& ranges, ShadingFeatures features, GLuint frameDepth);
    // The list-head image, the counter with its tile marks (cleared) and
    // the resolved tiles' draw, for a width x height image.
    void ensureImage(int width, int height);
    // Gathers the marked tiles into the resolve's indirect draw and clears the marks.
    void gatherTiles();
    // The fragments render() makes node storage for: a first guess, then what the last render listed.
    size_t wantedNodes(const ListedSegments& segments, int width, int height, size_t capacity,
                       uint64_t expectedFragments) const;
    // Pass 2: composites the gathered tiles' lists into the bound framebuffer (and their ids with `writeIds`).
    void resolveTiles(int width, int height, bool writeIds);
    // Reads back the last resolve's overlong and unwalked pixels and its resolved tiles.
    void readResolveCounts();

    ShadingPrograms listPrograms_;
    ShadingPrograms computePrograms_;
    Program resolveProgram_, tileProgram_;
    VertexArray emptyVertexArray_;
    Texture heads_;
    int headsWidth_ = 0, headsHeight_ = 0;
    Buffer nodes_, counter_, order_, tileDraw_;
    size_t nodeCapacity_ = 0;
    size_t listedLast_ = 0;  // fragments the last render that ran to its end listed, within its budget
    uint64_t overlongPixels_ = 0, unwalkedPixels_ = 0, resolvedTiles_ = 0, tilesInImage_ = 0;
    bool stopped_ = false;
};

}  // namespace hdhair::gl
