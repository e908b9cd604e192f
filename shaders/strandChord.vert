#version 450 core
#extension GL_GOOGLE_include_directive : require
// A light view's spans that strandTessellationLevel.glsl leaves one segment,
// drawn without the tessellator: line i joins the two ends (u = 0 and 1) of
// span drawOrder[i], the list LightViewSpans made, with what strand.tese
// would write there under HDHAIR_STRAND_LINES. The ends of a one-segment
// isoline are exactly these two points, so the texels are the same; on
// llvmpipe a patch costs its vertex, control and evaluation stages on the
// one thread that draws, whatever it emits, and most of a light view's
// spans are straight at its tolerance.
#include "include/frameUniforms.glsl"
#include "include/catmullRom.glsl"
#include "include/strandPoint.glsl"
#include "include/strandGeometry.glsl"
#include "include/strandLinePoint.glsl"

void main() {
    uint segment = drawOrder[uint(gl_VertexID) / 2u];
    float u = float(gl_VertexID % 2);
    vec4 positionWidth[4], colorOpacity[4];
    segmentControls(segment, positionWidth, colorOpacity);
    emitStrandLinePoint(evaluateStrandPoint(positionWidth, colorOpacity, u), segmentIds(int(segment)), u);
}
