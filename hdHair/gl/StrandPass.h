#pragma once
// Draws prepared curves (hdHair/curves/PreparedCurves.h) as camera-facing,
// Kajiya-Kay shaded ribbons: one patch of four Catmull-Rom control points per
// span, tessellated on the GPU (shaders/strand.*). Opaque and depth-tested.

#include <vector>

#include "hdHair/gl/GlObjects.h"
#include "hdHair/gl/UniformBlocks.h"

namespace hdhair {
struct PreparedCurves;
}

namespace hdhair::gl {

// The GPU copy of one prim's prepared curves: control points (vertex
// attributes) and each segment's curve index (a storage buffer, for elementId).
class StrandBuffer {
public:
    explicit StrandBuffer(const PreparedCurves& curves);
    GLuint buffer() const { return buffer_.get(); }
    GLuint segmentCurves() const { return segmentCurves_.get(); }
    GLsizei controlPointCount() const { return controlPointCount_; }

private:
    Buffer buffer_;
    Buffer segmentCurves_;
    GLsizei controlPointCount_ = 0;
};

// One prim to draw, with the id it writes into the primId output.
struct StrandDraw {
    const StrandBuffer* strands = nullptr;
    int primId = -1;
};

class StrandPass {
public:
    StrandPass();  // compiles the strand program; throws on driver errors
    void draw(const FrameUniforms& frame, const LightUniforms& lights, const std::vector<StrandDraw>& draws);

private:
    Program program_;
    VertexArray vertexArray_;
    Buffer frameBlock_, lightBlock_;
};

}  // namespace hdhair::gl
