#version 450 core
#extension GL_GOOGLE_include_directive : require
// shadowMode=reference: every fragment of a light's view appended to its
// texel's list (shadowFragmentLists.glsl), with its linear depth and its
// alpha (coverage x opacity in the light's pixels). A count-only
// draw (capacity at or below the count) sizes the pool first. The light is
// entry 0 of the shadow uniforms.
#include "include/shadingFeatures.glsl"
#include "include/frameUniforms.glsl"
#include "include/lights.glsl"
#include "include/shadowFragmentLists.glsl"
#include "include/shadows.glsl"

layout(location = 0) in vec3 worldPosition;
layout(location = 2) in vec4 colorAlpha;

// x: fragments offered so far (also past capacity), y: nodes the pool holds.
layout(std430, binding = 11) buffer ShadowNodeCounter {
    uint shadowNodeCount;
    uint shadowNodeCapacity;
};

void main() {
    float alpha = colorAlpha.a;
    if (alpha <= 0.0) return;
    uint index = atomicAdd(shadowNodeCount, 1u);
    if (index >= shadowNodeCapacity) return;
    uint previous = imageAtomicExchange(shadowListHeads, ivec3(ivec2(gl_FragCoord.xy), shadowSlot(0)), index);
    writeShadowNode(index, ShadowNode(shadowLinearDepth(0, worldPosition), alpha, previous));
}
