#pragma once
// Builds one light's deep opacity map (Yuksel & Keyser 2008, as Svoboda 2012
// section 2.7 implemented them) into its slot of gl::ShadowMapStorage: the
// nearest hair per texel (shadowDepth.frag, min-blended linear depth), then
// every fragment's alpha added into the layers behind it (deepOpacity.frag,
// additive blending into up to 8 RGBA16F draw buffers; its program is
// compiled for the layer count, so that it adds into only the layers there
// are). Both passes draw the
// strands the camera draws, through the light's view (LightViewDraw), or
// rasterise them as lines in compute (LightViewRaster). Meshes
// add a third: the nearest mesh per texel (meshShadowDepth.frag), the opaque
// occluders strands test against.

#include <cstdint>
#include <vector>

#include "hdHair/gl/GlObjects.h"
#include "hdHair/gl/LightViewDraw.h"
#include "hdHair/gl/LightViewRaster.h"
#include "hdHair/gl/LightViewSpans.h"
#include "hdHair/gl/MeshGeometry.h"
#include "hdHair/gl/MeshPass.h"
#include "hdHair/gl/SegmentRange.h"
#include "hdHair/gl/ShadingPrograms.h"
#include "hdHair/gl/ShadowMapStorage.h"
#include "hdHair/gl/StrandGeometry.h"
#include "hdHair/gl/UniformBlocks.h"

namespace hdhair::gl {

// How a light view draws the strands (PlannedShadow::strandLines,
// ::straightSpans and ::computeLines, from shadowStrandLines and strandRaster).
enum class LightViewStrands {
    Ribbons,           // camera-facing ribbons, as the camera draws them
    TessellatedLines,  // one-texel lines, every span through the tessellator
    Lines,             // one-texel lines, one-segment spans without it (LightViewSpans.h)
    ComputeLines,      // one-texel lines from the compute rasteriser (LightViewRaster.h)
};

// Spans of the light views, by how they were drawn: the LightViewStrands::Lines
// views' one-segment spans, drawn as plain lines, and the rest, drawn through
// the tessellator (culled spans count in neither); the spans the
// ComputeLines views gave the compute rasteriser (culled ones included:
// each invocation culls its own).
struct LightViewSpanCounts {
    uint64_t straight = 0, tessellated = 0, compute = 0;
};

class ShadowMapPass {
public:
    // Compiles the depth program, the opacity program on first use for each
    // layer count; both throw on driver errors.
    ShadowMapPass();

    // `light` names the light as entry 0 (its slot, view and layers).
    // With LightViewStrands::Lines the depth pass lists the view's spans
    // (LightViewSpans) and the opacity pass of the same view reuses the list.
    void renderDepth(ShadowMapStorage& storage, const StrandGeometry& geometry, const std::vector<SegmentRange>& ranges,
                     const FrameUniforms& lightView, const ShadowUniforms& light, LightViewStrands strands);
    void renderOpacity(ShadowMapStorage& storage, const StrandGeometry& geometry,
                       const std::vector<SegmentRange>& ranges, const FrameUniforms& lightView,
                       const ShadowUniforms& light, LightViewStrands strands);
    // The spans the views drew since the last call (which resets them).
    LightViewSpanCounts takeSpanCounts();
    void renderMeshDepth(ShadowMapStorage& storage, MeshPass& meshPass, const MeshGeometry& meshes,
                         const std::vector<MeshDraw>& draws, const FrameUniforms& lightView,
                         const ShadowUniforms& light);

private:
    // Draws `strands` with `programs` (and `straightPrograms` for the spans
    // listed as one segment) under `features`; `listAgain`: the view's list
    // is made first, else the last one is drawn.
    void drawStrands(ShadingPrograms& programs, ShadingPrograms& straightPrograms, ShadingFeatures features,
                     const StrandGeometry& geometry, const std::vector<SegmentRange>& ranges,
                     const FrameUniforms& lightView, const ShadowUniforms& light, LightViewStrands strands,
                     bool listAgain);

    ShadingPrograms depthPrograms_;    // every part, ribbons or lines
    ShadingPrograms opacityPrograms_;  // every part, with the layer count compiled in
    ShadingPrograms straightDepthPrograms_, straightOpacityPrograms_;  // strandChord.vert and the same parts
    LightViewDraw draw_;
    LightViewSpans spans_;
    LightViewRaster raster_;
    LightViewSpanCounts spanCounts_;
};

}  // namespace hdhair::gl
