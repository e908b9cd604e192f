#pragma once
// Sums light batches: the frame of lights 5-8 (and so on) is added onto the
// frame of lights 1-4, colour added, alpha kept (shaders/accumulateLightBatch.frag).

#include "hdHair/gl/GlObjects.h"

namespace hdhair::gl {

class RenderTarget;

class LightBatchAccumulation {
public:
    LightBatchAccumulation();
    // Adds `batch`'s resolved colour onto `frame`'s resolved colour.
    void add(RenderTarget& frame, const RenderTarget& batch);

private:
    Program program_;
    VertexArray emptyVertexArray_;
};

}  // namespace hdhair::gl
