#version 450 core
#extension GL_GOOGLE_include_directive : require
// Deep opacity maps, pass 2's end in compute: adds lightViewOpacity.comp's
// per-layer fixed-point sums (lightViewLayerSums.glsl) front to back into
// the cumulative opacity each layer holds (deepOpacity.frag's layers:
// everything up to its boundary), writes them
// into the slot's RGBA16F layers, 4 a texel, and zeroes the sums for the
// next map. One invocation a texel. The light is entry 0 of the shadow uniforms.
#include "include/shadingFeatures.glsl"
#include "include/lights.glsl"
#include "include/shadowFragmentLists.glsl"
#include "include/shadows.glsl"
#include "include/lightViewLayerSums.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(rgba16f, binding = 3) uniform writeonly image2DArray opacityLayers;

void main() {
    int resolution = shadows.mode.w;
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (texel.x >= resolution || texel.y >= resolution) return;
    int layers = shadowLayerCount();
    int targets = (layers + 3) / 4;
    float opacity = 0.0;
    for (int target = 0; target < targets; ++target) {
        vec4 value = vec4(0.0);
        for (int c = 0; c < 4; ++c) {
            int layer = 4 * target + c;
            if (layer >= layers) break;
            uint index = layerSumIndex(layer, texel, resolution);
            opacity += layerSumOpacity(index);
            layerSums[index] = 0u;
            value[c] = opacity;
        }
        imageStore(opacityLayers, ivec3(texel, shadowSlot(0) * targets + target), value);
    }
}
