#pragma once
// Builds one light's deep opacity map (Yuksel & Keyser 2008, as Svoboda 2012
// section 2.7 implemented them) into its slot of gl::ShadowMapStorage: the
// nearest hair per texel (shadowDepth.frag, min-blended linear depth), then
// every fragment's alpha added into the layers behind it (deepOpacity.frag,
// additive blending into up to 8 RGBA16F draw buffers; its program is
// compiled for the layer count, so that it adds into only the layers there
// are). Both passes draw the
// strands the camera draws, through the light's view (LightViewDraw). Meshes
// add a third: the nearest mesh per texel (meshShadowDepth.frag), the opaque
// occluders strands test against.

#include <vector>

#include "hdHair/gl/GlObjects.h"
#include "hdHair/gl/LightViewDraw.h"
#include "hdHair/gl/MeshGeometry.h"
#include "hdHair/gl/MeshPass.h"
#include "hdHair/gl/SegmentRange.h"
#include "hdHair/gl/ShadingPrograms.h"
#include "hdHair/gl/ShadowMapStorage.h"
#include "hdHair/gl/StrandGeometry.h"
#include "hdHair/gl/UniformBlocks.h"

namespace hdhair::gl {

class ShadowMapPass {
public:
    // Compiles the depth program, the opacity program on first use for each
    // layer count; both throw on driver errors.
    ShadowMapPass();

    // `light` names the light as entry 0 (its slot, view and layers);
    // `strandLines`: the strands are drawn as one-texel lines rather than
    // ribbons (ShadingFeatures::setStrandLines; PlannedShadow::strandLines).
    void renderDepth(ShadowMapStorage& storage, const StrandGeometry& geometry, const std::vector<SegmentRange>& ranges,
                     const FrameUniforms& lightView, const ShadowUniforms& light, bool strandLines);
    void renderOpacity(ShadowMapStorage& storage, const StrandGeometry& geometry,
                       const std::vector<SegmentRange>& ranges, const FrameUniforms& lightView,
                       const ShadowUniforms& light, bool strandLines);
    void renderMeshDepth(ShadowMapStorage& storage, MeshPass& meshPass, const MeshGeometry& meshes,
                         const std::vector<MeshDraw>& draws, const FrameUniforms& lightView,
                         const ShadowUniforms& light);

private:
    ShadingPrograms depthPrograms_;    // every part, ribbons or lines
    ShadingPrograms opacityPrograms_;  // every part, with the layer count compiled in
    LightViewDraw draw_;
};

}  // namespace hdhair::gl
