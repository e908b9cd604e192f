#version 450 core
#extension GL_GOOGLE_include_directive : require
// The nearest mesh per texel of a light's mesh view, as linear depth (world
// units along the light's viewing direction), min-blended into an R32F layer
// cleared to HDHAIR_NO_HAIR: the opaque occluders the strands and meshes test
// against (shadows.glsl meshTransmittance). The meshes come through mesh.vert
// with that view's view-projection; the light is entry 0 of the shadow
// uniforms.
#include "include/shadingFeatures.glsl"
#include "include/lights.glsl"
#include "include/shadowFragmentLists.glsl"
#include "include/shadows.glsl"

layout(location = 0) in vec3 worldPosition;

layout(location = 0) out float outDepth;

void main() { outDepth = meshLinearDepth(0, worldPosition); }
