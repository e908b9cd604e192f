#version 450 core
#extension GL_GOOGLE_include_directive : require
// Exact transparency, pass 1: shades each strand fragment like strand.frag
// and appends it to its pixel's list instead of blending it. Fragments hidden
// by opaque geometry are rejected before shading (early depth test).
#include "include/shadingFeatures.glsl"
#include "include/frameUniforms.glsl"
#include "include/lights.glsl"
#include "include/kajiyaKay.glsl"
#include "include/marschner.glsl"
#include "include/marschnerAnalytic.glsl"
#include "include/dualScattering.glsl"
#include "include/catmullRom.glsl"
#include "include/strandGeometry.glsl"
#include "include/hairMaterials.glsl"
#include "include/shadowFragmentLists.glsl"
#include "include/shadows.glsl"
#include "include/srbfLighting.glsl"
#include "include/strandShading.glsl"
#define HDHAIR_FRAGMENT_LIST_APPEND 1
#include "include/fragmentLists.glsl"

layout(early_fragment_tests) in;

layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec3 worldTangent;
layout(location = 2) in vec4 colorAlpha;
layout(location = 3) flat in ivec4 ids;  // primId, elementId, material, segment
layout(location = 4) in float spanU;
layout(location = 5) in vec3 strandCentre;

void main() {
    float alpha = colorAlpha.a;
    if (alpha <= 0.0) return;
    vec3 radiance = strandRadiance(worldPosition, strandCentre, worldTangent, colorAlpha.rgb, ids.z, ids.w, spanU);
    appendFragmentNode(ivec2(gl_FragCoord.xy), vec4(radiance * alpha, alpha), gl_FragCoord.z, ids.w);
}
