#pragma once
// A light view's deep opacity map drawn by the compute rasteriser, for views
// that draw the strands as one-texel lines (PlannedShadow::computeLines):
// the same two passes as ShadowMapPass's draws, with every span a compute
// invocation (shaders/include/lightViewLines.glsl) instead of a patch or a
// line through the vertex stages, which llvmpipe runs on the one thread that
// draws. The depth pass takes an atomic minimum into the slot's R32F layer
// (lightViewDepth.comp). The opacity pass adds each texel's alpha into the
// one layer it starts counting in, as fixed-point integers in a buffer of
// resolution^2 x layers (lightViewOpacity.comp; integer sums do not depend on
// the order, so a map rebuilt is the same to the bit), then sums them front
// to back into the slot's RGBA16F layers (lightViewLayers.comp), which
// clears the buffer for the next map. The shadow uniforms (binding 2) and the
// light view's frame uniforms (binding 0) must be bound, as for the draws.

#include <cstddef>
#include <vector>

#include "hdHair/gl/GlObjects.h"
#include "hdHair/gl/SegmentRange.h"
#include "hdHair/gl/ShadingPrograms.h"
#include "hdHair/gl/ShadowMapStorage.h"
#include "hdHair/gl/StrandGeometry.h"
#include "hdHair/gl/UniformBlocks.h"

namespace hdhair::gl {

class LightViewRaster {
public:
    LightViewRaster();  // compiles nothing: frames without compute light views never pay for it

    // `light` names the light as entry 0 (its slot, view and layers), as
    // the bound shadow uniforms do. The nearest hair of `ranges` in its
    // slot's depth layer, cleared first:
    void renderDepth(ShadowMapStorage& storage, const StrandGeometry& geometry, const std::vector<SegmentRange>& ranges,
                     const ShadowUniforms& light);
    // the opacity layers behind it (renderDepth must have drawn the slot).
    void renderOpacity(ShadowMapStorage& storage, const StrandGeometry& geometry,
                       const std::vector<SegmentRange>& ranges, const ShadowUniforms& light);

    // The bytes the per-layer sums take for maps of `resolution`^2 texels
    // and `layers` layers (the plan keeps views whose sums would not fit in
    // shadowMemoryMB on the draws).
    static size_t layerSumBytes(int resolution, int layers);

private:
    void dispatchSpans(const Program& program, const std::vector<SegmentRange>& ranges);

    ShadingPrograms depthPrograms_, opacityPrograms_, layerPrograms_;
    Buffer layerSums_;
    size_t layerSumCapacity_ = 0;
};

}  // namespace hdhair::gl
