#version 450 core
#extension GL_GOOGLE_include_directive : require
// Deep opacity maps, pass 1 (Yuksel & Keyser 2008; Svoboda 2012 section
// 2.7.2): the nearest hair per texel of a light's view, as linear depth
// (world units along the light's viewing direction), min-blended into an
// R32F layer cleared to HDHAIR_NO_HAIR, so drawing order does not matter.
// The strands come through strand.vert/.tesc/.tese with the light view's
// frame uniforms: ribbons facing the light (strand.geom), or one-texel lines
// (HDHAIR_STRAND_LINES, no geometry shader), tessellated and covered by the
// same rules in the light's pixels. The light is entry 0 of the shadow
// uniforms.
#include "include/shadingFeatures.glsl"
#include "include/frameUniforms.glsl"
#include "include/lights.glsl"
#include "include/shadowFragmentLists.glsl"
#include "include/shadows.glsl"

layout(location = 0) in vec3 worldPosition;
layout(location = 2) in vec4 colorAlpha;  // displayColor, opacity x coverage in the light's pixels

layout(location = 0) out float outDepth;

void main() {
    if (colorAlpha.a <= 0.0) discard;  // opacity 0 casts nothing
    outDepth = shadowLinearDepth(0, worldPosition);
}
