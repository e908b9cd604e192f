#pragma once
// Draws the frame's strands (StrandGeometry) as camera-facing ribbons: one
// patch of four Catmull-Rom control points per segment, tessellated on the
// GPU (shaders/strand.*), either opaque (depth written) or pre-multiplied and
// blended in a given far-to-near order (depth tested, not written; the
// nearest-depth image, when the target has one, min-blended).

#include <cstdint>
#include <vector>

#include "hdHair/gl/GlObjects.h"
#include "hdHair/gl/SegmentRange.h"
#include "hdHair/gl/ShadingPrograms.h"
#include "hdHair/gl/StrandGeometry.h"
#include "hdHair/gl/UniformBlocks.h"

namespace hdhair::gl {

enum class StrandBlending {
    Opaque,          // no blending, depth test and write: the opaque path
    PremultipliedOver,  // ONE, ONE_MINUS_SRC_ALPHA, depth test only; nearest depth min-blended
    IdsOnly  // ids of the nearest strand fragment (depth test and write); no colour, no nearest depth
};

class StrandPass {
public:
    StrandPass();

    // Uploads and binds the frame's uniform blocks (also used by other
    // passes): frame at 0, lights at 1, their shadows at 2. The draws after
    // it use the strand program compiled with `features`
    // (what the frame's plan says the draw reaches, or ShadingFeatures::all()),
    // compiled now if no draw has used it before; throws on driver errors.
    void setUniforms(const FrameUniforms& frame, const LightUniforms& lights, const ShadowUniforms& shadows,
                     ShadingFeatures features);

    // Sends the frame's drawing order (segments far to near), once a frame:
    // every light batch draws with it.
    void setDrawOrder(const std::vector<uint32_t>& order);

    // Draws the strands: in the order set by setDrawOrder() when the frame
    // uniforms' orderedDraw is 1, else the `ranges` of the geometry (the
    // drawn prims' segments) as they lie. setUniforms() must have been called.
    void draw(const StrandGeometry& geometry, const std::vector<SegmentRange>& ranges, StrandBlending blending);

    // Triangles the colour draws over the strands made since the last call
    // (GL_PRIMITIVES_GENERATED: what the tessellator made, culled spans
    // excluded; every light batch's pass counted), then forgets them; 0 when
    // none ran. Waits for those draws: call it after the frame's readback.
    uint64_t takeTriangles();

private:
    ShadingPrograms programs_;
    const Program* program_ = nullptr;  // setUniforms()'s
    VertexArray emptyVertexArray_;  // core profile draws need one bound
    Buffer frameBlock_, lightBlock_, shadowBlock_, orderBuffer_;
    size_t orderCapacity_ = 0, orderedSegments_ = 0;
    float maxSegmentsPerSpan_ = 8.0f;
    bool orderedDraw_ = false;
    // One query a colour draw since the last takeTriangles(); kept for reuse.
    std::vector<Query> triangleQueries_;
    size_t triangleQueriesUsed_ = 0;
};

}  // namespace hdhair::gl
