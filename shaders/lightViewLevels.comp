#version 450 core
#extension GL_GOOGLE_include_directive : require
// The segments strand.tesc would cut each span of a range into in this
// pass's view (strandTessellationLevel.glsl, the light view's frame
// uniforms): LightViewSpans reads them back and draws the one-segment spans
// as plain lines (strandChord.vert), the rest through the tessellator.
#include "include/frameUniforms.glsl"
#include "include/strandGeometry.glsl"
#include "include/strandTessellationLevel.glsl"

layout(local_size_x = 64) in;

// Per segment of the range, from levelFirst on: 0 culled, else the level.
layout(std430, binding = 0) writeonly buffer SegmentLevels {
    uint segmentLevels[];
};
layout(location = 0) uniform uint rangeFirst;
layout(location = 1) uniform uint rangeCount;
layout(location = 2) uniform uint levelFirst;

void main() {
    uint index = gl_GlobalInvocationID.x;
    if (index >= rangeCount) return;
    vec4 positionWidth[4], colorOpacity[4];
    segmentControls(rangeFirst + index, positionWidth, colorOpacity);
    segmentLevels[levelFirst + index] = uint(strandTessellationLevel(positionWidth, colorOpacity));
}
