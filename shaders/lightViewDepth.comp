#version 450 core
#extension GL_GOOGLE_include_directive : require
// Deep opacity maps, pass 1, in compute (lightViewLines.glsl): the nearest
// hair per texel of a light's view, as shadowDepth.frag finds it, written
// with an atomic minimum on the depth's bits. The R32F layer is bound as
// R32UI (compatible by size), cleared to HDHAIR_NO_HAIR; non-negative floats
// order as their bits do, and depths in front of the near plane are clipped
// away. The light is entry 0 of the shadow uniforms.
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

layout(local_size_x = 32) in;

layout(r32ui, binding = 2) uniform uimage2DArray hairDepths;
layout(location = 0) uniform uint rangeFirst;
layout(location = 1) uniform uint rangeCount;

void lightViewTexel(ivec2 texel, vec3 world, float alpha) {
    if (alpha <= 0.0) return;  // opacity 0 casts nothing
    float depth = max(shadowLinearDepth(0, world), 0.0);
    imageAtomicMin(hairDepths, ivec3(texel, shadowSlot(0)), floatBitsToUint(depth));
}

void main() {
    uint index = gl_GlobalInvocationID.x;
    if (index < rangeCount) rasterizeLightViewSpan(rangeFirst + index);
}
