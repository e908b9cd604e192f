#version 450 core
#extension GL_GOOGLE_include_directive : require
// Evaluates the Catmull-Rom span at u, one point of its centre-line
// polyline (isolines), with the vector across the strand's width (a
// world-space diameter) perpendicular to both the tangent and the view;
// strand.geom widens each segment of the polyline into a camera-facing quad.
// Isolines rather than a quad domain: a quad domain rounds the across-strand
// inner level 1 up to 2, which made about 4n triangles and 3n evaluations
// of n segments; this makes 2n triangles from n + 1 evaluations, and on
// llvmpipe, which tessellates on one thread, the geometry is the serial part.
//
// With vertex shadows (shadowSampling; HDHAIR_VERTEX_SHADOWS, which only the
// camera's strand programs define, is how many of the pass's lights have a
// map, counted to the last) it also looks up their deep opacity maps at the
// point: every lookup is taken on the centre line, so across the ribbon it
// is the same anyway, and along the segment the fragments interpolate it.
// One lookup a point instead of one a fragment, which on llvmpipe was most
// of the strand pass's shading.
//
// The ribbon's width, colour and sub-pixel coverage are strandRibbonPoint.glsl's.
//
// Strand lines (HDHAIR_STRAND_LINES): the isolines go to the rasteriser as
// one-pixel lines, whose vertices strandLinePoint.glsl writes.
#include "include/frameUniforms.glsl"
#include "include/catmullRom.glsl"
#include "include/strandPoint.glsl"
#include "include/strandGeometry.glsl"
#include "include/shadingFeatures.glsl"
#ifdef HDHAIR_VERTEX_SHADOWS
#include "include/lights.glsl"
#include "include/shadowFragmentLists.glsl"
#include "include/shadows.glsl"
#endif
#include "include/strandRibbonPoint.glsl"

layout(isolines, equal_spacing) in;

layout(location = 0) in vec4 tcsPositionWidth[];
layout(location = 1) in vec4 tcsColorOpacity[];
layout(location = 2) flat in int tcsSegment[];

#if defined(HDHAIR_STRAND_LINES) && defined(HDHAIR_VERTEX_SHADOWS)
#error "strand lines are for the light views, which read no shadows"
#endif
#ifdef HDHAIR_STRAND_LINES
#include "include/strandLinePoint.glsl"
#else
layout(location = 0) out vec3 tesCentre;    // the centre line at u
layout(location = 1) out vec3 tesAcross;    // from one edge of the ribbon to the other
layout(location = 2) out vec3 tesTangent;
layout(location = 3) out vec4 tesColorAlpha;  // displayColor, opacity x coverage
layout(location = 4) flat out ivec4 tesIds;   // primId, elementId, material, segment
layout(location = 5) out float tesSpanU;
#endif
#ifdef HDHAIR_VERTEX_SHADOWS
layout(location = 6) out vec4 tesTransmittance[HDHAIR_VERTEX_SHADOW_VECTORS];  // 4 lights a vec4, at the centre line
#endif

void main() {
    float u = gl_TessCoord.x;
    vec4 positionWidth[4] = vec4[4](tcsPositionWidth[0], tcsPositionWidth[1], tcsPositionWidth[2], tcsPositionWidth[3]);
    vec4 colorOpacity[4] = vec4[4](tcsColorOpacity[0], tcsColorOpacity[1], tcsColorOpacity[2], tcsColorOpacity[3]);
    StrandPoint point = evaluateStrandPoint(positionWidth, colorOpacity, u);
    int segment = tcsSegment[0];
    ivec4 pointIds = segmentIds(segment);
#ifdef HDHAIR_STRAND_LINES
    emitStrandLinePoint(point, pointIds, u);
#else
    RibbonPoint ribbon = strandRibbonPoint(point);
    tesCentre = ribbon.centre;
    tesAcross = ribbon.across;
    tesTangent = ribbon.tangent;
    tesColorAlpha = ribbon.colorAlpha;
    tesIds = pointIds;
    tesSpanU = u;
#endif
#ifdef HDHAIR_VERTEX_SHADOWS
    vec4 transmittance[HDHAIR_VERTEX_SHADOW_VECTORS];
    vertexShadowTransmittance(tesCentre, transmittance);
    tesTransmittance = transmittance;
#endif
}
