#version 450 core
#extension GL_GOOGLE_include_directive : require
// Cuts each Catmull-Rom span into strandTessellationLevel.glsl's segments;
// a culled span gets no line (outer level 0), which discards it.
#include "include/frameUniforms.glsl"
#include "include/strandTessellationLevel.glsl"

layout(vertices = 4) out;

layout(location = 0) in vec4 vsPositionWidth[];
layout(location = 1) in vec4 vsColorOpacity[];
layout(location = 2) flat in int vsSegment[];
layout(location = 0) out vec4 tcsPositionWidth[];
layout(location = 1) out vec4 tcsColorOpacity[];
layout(location = 2) flat out int tcsSegment[];

void main() {
    tcsPositionWidth[gl_InvocationID] = vsPositionWidth[gl_InvocationID];
    tcsColorOpacity[gl_InvocationID] = vsColorOpacity[gl_InvocationID];
    tcsSegment[gl_InvocationID] = vsSegment[gl_InvocationID];
    if (gl_InvocationID != 0) return;

    vec4 positionWidth[4] = vec4[4](vsPositionWidth[0], vsPositionWidth[1], vsPositionWidth[2], vsPositionWidth[3]);
    vec4 colorOpacity[4] = vec4[4](vsColorOpacity[0], vsColorOpacity[1], vsColorOpacity[2], vsColorOpacity[3]);
    float level = strandTessellationLevel(positionWidth, colorOpacity);

    // Isolines: one line (outer 0) of `level` segments along the span
    // (outer 1); strand.geom widens each segment into a quad.
    gl_TessLevelOuter[0] = level > 0.0 ? 1.0 : 0.0;
    gl_TessLevelOuter[1] = level;
}
