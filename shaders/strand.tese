#version 450 core
#extension GL_GOOGLE_include_directive : require
// Evaluates the Catmull-Rom span at u and offsets across the strand's width
// (a world-space diameter) perpendicular to both the tangent and the view:
// a camera-facing ribbon.
//
// Sub-pixel coverage (Svoboda 2012, section 1.2.3): a strand whose projected
// width is below frame.minPixelWidth is drawn that wide instead, with its
// alpha scaled by true width / drawn width, so thin hair fades with distance
// instead of breaking up into dashes or vanishing.
#include "include/frameUniforms.glsl"
#include "include/catmullRom.glsl"
#include "include/strandGeometry.glsl"

layout(quads, equal_spacing, ccw) in;

layout(location = 0) in vec4 tcsPositionWidth[];
layout(location = 1) in vec4 tcsColorOpacity[];
layout(location = 2) flat in int tcsSegment[];

layout(location = 0) out vec3 worldPosition;
layout(location = 1) out vec3 worldTangent;
layout(location = 2) out vec4 colorAlpha;  // displayColor, opacity x coverage
layout(location = 3) flat out ivec4 ids;   // primId, elementId, material, segment
layout(location = 4) out float spanU;      // where on the span: per-point hair parameters
layout(location = 5) out vec3 strandCentre;  // the centre line under this point: where shadows are looked up

void main() {
    float u = gl_TessCoord.x, v = gl_TessCoord.y;
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
    float drawnWidth = width;
    if (frame.minPixelWidth > 0.0) {
        float clipW = max(abs((frame.viewProjection * vec4(positionWidth.xyz, 1.0)).w), 1e-12);
        float widthPixels = width * frame.pixelsPerUnit / clipW;
        if (widthPixels < frame.minPixelWidth) {
            drawnWidth = frame.minPixelWidth * clipW / frame.pixelsPerUnit;
            opacity *= widthPixels / frame.minPixelWidth;
        }
    }
    vec3 position = positionWidth.xyz + side * ((v - 0.5) * drawnWidth);

    worldPosition = position;
    worldTangent = tangent;
    colorAlpha = vec4(max(shade.rgb, vec3(0.0)), opacity);
    int segment = tcsSegment[0];
    ids = ivec4(segmentPrimAndInstance(segment).x, segmentCurve[segment], segmentMaterial(segment), segment);
    spanU = u;
    strandCentre = positionWidth.xyz;
    gl_Position = frame.viewProjection * vec4(position, 1.0);
}
