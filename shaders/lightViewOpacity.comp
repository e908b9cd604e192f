#version 450 core
#extension GL_GOOGLE_include_directive : require
// Deep opacity maps, pass 2, in compute (lightViewLines.glsl): each texel's
// alpha goes to the one layer it starts counting in, the first whose
// boundary lies behind it, d = z - z0 < d_k (the last layer for anything
// further), as a fixed-point sum (lightViewLayerSums.glsl says why);
// lightViewLayers.comp then adds the layers up front to back into the
// cumulative opacities deepOpacity.frag blends into the RGBA16F layers, one
// atomic a texel rather than one a layer. z0 comes from pass 1 at this very
// texel. The light is entry 0 of the shadow uniforms.
#define HDHAIR_COMPUTE_RASTER 1
#include "include/shadingFeatures.glsl"
#include "include/frameUniforms.glsl"
#include "include/lights.glsl"
#include "include/shadowFragmentLists.glsl"
#include "include/shadows.glsl"
#include "include/catmullRom.glsl"
#include "include/strandPoint.glsl"
#include "include/strandGeometry.glsl"
#include "include/strandTessellationLevel.glsl"
#include "include/strandLinePoint.glsl"
#include "include/lightViewLines.glsl"
#include "include/lightViewLayerSums.glsl"

layout(local_size_x = 32) in;

layout(location = 0) uniform uint rangeFirst;
layout(location = 1) uniform uint rangeCount;

void lightViewTexel(ivec2 texel, vec3 world, float alpha) {
    if (alpha <= 0.0) return;
    float z0 = texelFetch(shadowDepths, ivec3(texel, shadowSlot(0)), 0).r;
    float d = shadowLinearDepth(0, world) - z0;
    float scale = shadows.lightMap[0].y;
    int layers = shadowLayerCount();
    int layer = 0;
    while (layer < layers - 1 && !(d < shadowLayerBoundary(layer) * scale)) ++layer;
    addToLayerSum(layerSumIndex(layer, texel, shadows.mode.w), alpha);
}

void main() {
    uint index = gl_GlobalInvocationID.x;
    if (index < rangeCount) rasterizeLightViewSpan(rangeFirst + index);
}
