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
// Strand lines (HDHAIR_STRAND_LINES, the light views' shadowStrandLines when
// no strand is over 1.5 texels wide there): no geometry shader; the
// isolines are rasterised as one-pixel lines, with the fragment stage's
// inputs written here. A line lights one pixel per step along its major
// axis: m pixels per pixel of its length, m = max(|dx|, |dy|) / |(dx, dy)|
// of its screen direction (1 along an axis, 1/sqrt(2) diagonally), where a
// ribbon of the true width covers `width in pixels` of area. So each pixel
// takes alpha opacity x width in pixels / m, and the opacity the pixels sum
// is the ribbon's at every angle: above 1 for a strand wider than the line
// (RenderPlan.cpp's kMaxStrandLineTexels bounds how much wider).
#include "include/frameUniforms.glsl"
#include "include/catmullRom.glsl"
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
// What strand.geom hands the fragment stage, at its locations.
layout(location = 0) out vec3 worldPosition;
layout(location = 1) out vec3 worldTangent;
layout(location = 2) out vec4 colorAlpha;  // displayColor, opacity x coverage
layout(location = 3) flat out ivec4 ids;   // primId, elementId, material, segment
layout(location = 4) out float spanU;
layout(location = 5) out vec3 strandCentre;
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
    vec4 w = catmullRomWeights(u);
    vec4 dw = catmullRomDerivativeWeights(u);

    vec4 positionWidth = vec4(0.0);
    vec3 tangent = vec3(0.0);
    vec4 shade = vec4(0.0);
    for (int i = 0; i < 4; ++i) {
        positionWidth += w[i] * tcsPositionWidth[i];
        tangent += dw[i] * tcsPositionWidth[i].xyz;
        shade += w[i] * tcsColorOpacity[i];
    }
    // A zero-length derivative (coincident control points) falls back to the
    // chord, then to any axis: the ribbon must stay well defined.
    if (dot(tangent, tangent) < 1e-20) tangent = tcsPositionWidth[2].xyz - tcsPositionWidth[1].xyz;
    if (dot(tangent, tangent) < 1e-20) tangent = vec3(0.0, 1.0, 0.0);
    tangent = normalize(tangent);

    vec3 toEye = directionToEye(positionWidth.xyz);
    vec3 side = cross(tangent, toEye);
    if (dot(side, side) < 1e-12) side = cross(tangent, abs(tangent.x) < 0.9 ? vec3(1, 0, 0) : vec3(0, 1, 0));
    side = normalize(side);

    // Cubic interpolation can overshoot: widths, colours and opacities are clamped.
    float width = max(positionWidth.w, 0.0);
    float opacity = clamp(shade.a, 0.0, 1.0);
    int segment = tcsSegment[0];
    ivec4 pointIds = ivec4(segmentPrimAndInstance(segment).x, segmentCurve[segment], segmentMaterial(segment), segment);
#ifdef HDHAIR_STRAND_LINES
    vec4 clip = frame.viewProjection * vec4(positionWidth.xyz, 1.0);
    float clipW = max(abs(clip.w), 1e-12);
    // The tangent's screen direction: d(clip.xy / clip.w) along it, in
    // pixels (the common factor 1 / w^2 dropped).
    vec4 clipTangent = frame.viewProjection * vec4(tangent, 0.0);
    vec2 screen = (clipTangent.xy * clip.w - clip.xy * clipTangent.w) * frame.viewportSize;
    float screenLength = length(screen);
    // End-on (no screen direction) the line is a point: m = 1.
    float m = screenLength > 0.0 ? clamp(max(abs(screen.x), abs(screen.y)) / screenLength, 0.70710678, 1.0) : 1.0;
    float widthPixels = width * frame.pixelsPerUnit / clipW;
    worldPosition = positionWidth.xyz;
    strandCentre = positionWidth.xyz;
    worldTangent = tangent;
    colorAlpha = vec4(max(shade.rgb, vec3(0.0)), opacity * widthPixels / m);
    ids = pointIds;
    spanU = u;
    gl_Position = clip;
#else
    float drawnWidth = width;
    if (frame.minPixelWidth > 0.0) {
        float clipW = max(abs((frame.viewProjection * vec4(positionWidth.xyz, 1.0)).w), 1e-12);
        float widthPixels = width * frame.pixelsPerUnit / clipW;
        if (widthPixels < frame.minPixelWidth) {
            drawnWidth = frame.minPixelWidth * clipW / frame.pixelsPerUnit;
            opacity *= widthPixels / frame.minPixelWidth;
        }
    }
    tesCentre = positionWidth.xyz;
    tesAcross = side * drawnWidth;
    tesTangent = tangent;
    tesColorAlpha = vec4(max(shade.rgb, vec3(0.0)), opacity);
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
