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
// Sub-pixel coverage (Svoboda 2012, section 1.2.3): a strand whose projected
// width is below frame.minPixelWidth is drawn that wide instead, with its
// alpha scaled by true width / drawn width, so thin hair fades with distance
// instead of breaking up into dashes or vanishing.
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
    vec3 toEye = directionToEye(point.positionWidth.xyz);
    vec3 side = cross(point.tangent, toEye);
    if (dot(side, side) < 1e-12)
        side = cross(point.tangent, abs(point.tangent.x) < 0.9 ? vec3(1, 0, 0) : vec3(0, 1, 0));
    side = normalize(side);

    // Cubic interpolation can overshoot: widths, colours and opacities are clamped.
    float width = max(point.positionWidth.w, 0.0);
    float opacity = clamp(point.shade.a, 0.0, 1.0);
    float drawnWidth = width;
    if (frame.minPixelWidth > 0.0) {
        float clipW = max(abs((frame.viewProjection * vec4(point.positionWidth.xyz, 1.0)).w), 1e-12);
        float widthPixels = width * frame.pixelsPerUnit / clipW;
        if (widthPixels < frame.minPixelWidth) {
            drawnWidth = frame.minPixelWidth * clipW / frame.pixelsPerUnit;
            opacity *= widthPixels / frame.minPixelWidth;
        }
    }
    tesCentre = point.positionWidth.xyz;
    tesAcross = side * drawnWidth;
    tesTangent = point.tangent;
    tesColorAlpha = vec4(max(point.shade.rgb, vec3(0.0)), opacity);
    tesIds = pointIds;
    tesSpanU = u;
#endif
#ifdef HDHAIR_VERTEX_SHADOWS
    for (int v = 0; v < HDHAIR_VERTEX_SHADOW_VECTORS; ++v) tesTransmittance[v] = vec4(1.0);
    for (int i = 0; i < HDHAIR_VERTEX_SHADOWS; ++i)
        tesTransmittance[i / 4][i % 4] =
            isSrbfLight(i) ? srbfShadowTransmittance(i, tesCentre) : shadowTransmittance(i, tesCentre);
#endif
}
