#version 450 core
#extension GL_GOOGLE_include_directive : require
// Deep opacity maps, pass 2 (Yuksel & Keyser 2008; Svoboda 2012 sections
// 1.5.4 and 2.7.2): every fragment adds its alpha (coverage x opacity in
// the light's pixels) to each layer that ends behind it, d = z - z0 < d_k,
// with additive blending (ONE, ONE) into RGBA16F targets, 4 layers each: the
// layers hold cumulative opacity. Fragments beyond the last layer count in
// the last (the thesis's option (b)), so layer K holds all the hair along
// the texel. The light is entry 0 of the shadow uniforms; z0 comes from
// pass 1 (shadowDepth.frag) at this very texel.
#include "include/shadingFeatures.glsl"
#include "include/frameUniforms.glsl"
#include "include/lights.glsl"
#include "include/shadowFragmentLists.glsl"
#include "include/shadows.glsl"

layout(location = 0) in vec3 worldPosition;
layout(location = 2) in vec4 colorAlpha;

// Layers 4t..4t+3 in target t: up to 32 layers in 8 draw buffers.
layout(location = 0) out vec4 outLayers[8];

void main() {
    float alpha = colorAlpha.a;
    if (alpha <= 0.0) discard;
    int slot = shadowSlot(0);
    float z0 = texelFetch(shadowDepths, ivec3(ivec2(gl_FragCoord.xy), slot), 0).r;
    float d = shadowLinearDepth(0, worldPosition) - z0;
    float scale = shadows.lightMap[0].y;
    // A constant in the program ShadowMapPass compiles (shadows.glsl), so
    // that only the targets there are get written.
    int layers = shadowLayerCount();
    for (int target = 0; target < HDHAIR_SHADOW_LAYER_VECTORS; ++target) {
        vec4 value = vec4(0.0);
        for (int c = 0; c < 4; ++c) {
            int layer = 4 * target + c;
            bool counts = layer < layers && (layer == layers - 1 || d < shadowLayerBoundary(layer) * scale);
            value[c] = counts ? alpha : 0.0;
        }
        outLayers[target] = value;
    }
}
