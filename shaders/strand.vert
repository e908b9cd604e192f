#version 450 core
#extension GL_GOOGLE_include_directive : require
// Pulls each patch's four Catmull-Rom control points from the combined
// geometry, in drawing order: vertex 4p + k is control point k of the p-th
// segment drawn (shared with the curve's neighbouring spans). No vertex attributes, so a sorted frame needs no index buffer.
#include "include/frameUniforms.glsl"
#include "include/strandGeometry.glsl"

layout(location = 0) out vec4 vsPositionWidth;
layout(location = 1) out vec4 vsColorOpacity;
layout(location = 2) flat out int vsSegment;

void main() {
    uint patchIndex = uint(gl_VertexID) / 4u;
    uint corner = uint(gl_VertexID) % 4u;
    uint segment = frame.orderedDraw != 0 ? drawOrder[patchIndex] : patchIndex;
    uint controlPoint = segmentFirstControl[segment] + corner;
    vsPositionWidth = controlPoints[2u * controlPoint];
    vsColorOpacity = controlPoints[2u * controlPoint + 1u];
    vsSegment = int(segment);
}
