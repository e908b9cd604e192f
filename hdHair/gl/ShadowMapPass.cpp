#include "hdHair/gl/ShadowMapPass.h"

#include <utility>

namespace hdhair::gl {

ShadowMapPass::ShadowMapPass()
    : depthPrograms_({"strand.vert", "strand.tesc", "strand.tese", "strand.geom", "shadowDepth.frag"}),
      opacityPrograms_({"strand.vert", "strand.tesc", "strand.tese", "strand.geom", "deepOpacity.frag"}),
      straightDepthPrograms_({"strandChord.vert", "shadowDepth.frag"}),
      straightOpacityPrograms_({"strandChord.vert", "deepOpacity.frag"}) {
    depthPrograms_.get(ShadingFeatures::all());  // compile errors surface here, not mid-frame
    checkGlError("setting up the shadow map passes");
}

void ShadowMapPass::renderDepth(ShadowMapStorage& storage, const StrandGeometry& geometry,
                                const std::vector<SegmentRange>& ranges, const FrameUniforms& lightView,
                                const ShadowUniforms& light, LightViewStrands strands) {
    if (strands == LightViewStrands::ComputeLines) {
        draw_.bindBlocks(lightView, light);
        raster_.renderDepth(storage, geometry, ranges, light);
        for (const SegmentRange& range : ranges) spanCounts_.compute += range.count;
        return;
    }
    storage.bindDepthTarget(int(light.lightMap[0].x));
    // The least depth wins, in any drawing order.
    glEnable(GL_BLEND);
    glBlendEquation(GL_MIN);
    drawStrands(depthPrograms_, straightDepthPrograms_, ShadingFeatures::all(), geometry, ranges, lightView, light,
                strands, true);
    glBlendEquation(GL_FUNC_ADD);
    glDisable(GL_BLEND);
    checkGlError("drawing a shadow depth map");
}

void ShadowMapPass::renderOpacity(ShadowMapStorage& storage, const StrandGeometry& geometry,
                                  const std::vector<SegmentRange>& ranges, const FrameUniforms& lightView,
                                  const ShadowUniforms& light, LightViewStrands strands) {
    if (strands == LightViewStrands::ComputeLines) {
        draw_.bindBlocks(lightView, light);
        raster_.renderOpacity(storage, geometry, ranges, light);
        return;
    }
    storage.bindOpacityTargets(int(light.lightMap[0].x));
    storage.bindForLookup();  // the nearest depths, drawn by renderDepth
    // Sums in any drawing order (thesis section 2.7.2: additive blending).
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    // With the layer count a constant, deepOpacity.frag adds into those
    // layers alone, not all 32 under a uniform test (on llvmpipe a quarter of
    // the TressFX bear's opacity pass).
    drawStrands(opacityPrograms_, straightOpacityPrograms_, ShadingFeatures::all().setShadowLayers(light.mode.y),
                geometry, ranges, lightView, light, strands, !spans_.builtFor(ranges, lightView));
    glDisable(GL_BLEND);
    checkGlError("drawing deep opacity layers");
}

LightViewSpanCounts ShadowMapPass::takeSpanCounts() { return std::exchange(spanCounts_, {}); }

void ShadowMapPass::drawStrands(ShadingPrograms& programs, ShadingPrograms& straightPrograms, ShadingFeatures features,
                                const StrandGeometry& geometry, const std::vector<SegmentRange>& ranges,
                                const FrameUniforms& lightView, const ShadowUniforms& light, LightViewStrands strands,
                                bool listAgain) {
    const ShadingFeatures drawn = features.setStrandLines(strands != LightViewStrands::Ribbons);
    if (strands != LightViewStrands::Lines) {
        draw_.draw(programs.get(drawn), geometry, ranges, lightView, light);
        return;
    }
    if (listAgain) {
        draw_.bindBlocks(lightView, light);
        spans_.build(geometry, ranges, lightView);
        spanCounts_.straight += spans_.straight();
        spanCounts_.tessellated += spans_.tessellated();
    }
    draw_.draw(straightPrograms.get(drawn), programs.get(drawn), geometry, spans_, lightView, light);
}

void ShadowMapPass::renderMeshDepth(ShadowMapStorage& storage, MeshPass& meshPass, const MeshGeometry& meshes,
                                    const std::vector<MeshDraw>& draws, const FrameUniforms& lightView,
                                    const ShadowUniforms& light) {
    storage.bindMeshDepthTarget(int(light.meshMap[0].x));
    draw_.bindBlocks(lightView, light);
    meshPass.draw(meshes, draws, lightView.viewProjection, MeshShading::LightDepth);
    checkGlError("drawing a mesh shadow depth map");
}

}  // namespace hdhair::gl
