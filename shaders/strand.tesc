#version 450 core
#extension GL_GOOGLE_include_directive : require
// Chooses how finely each Catmull-Rom span is cut: by its projected length in
// the tessellation view, so strands far away or seen end-on cost few segments
// (adaptive to projected size), never more than maxSegmentsPerSpan. The
// tessellation view is the camera's (or the camera the shadow maps were built
// with, hdHair/render/TessellationView.h) in every pass, light views
// included, so each view draws the same curve. Culling is per view: spans
// wholly outside this pass's frustum get level 0, which discards them.
#include "include/frameUniforms.glsl"

layout(vertices = 4) out;

layout(location = 0) in vec4 vsPositionWidth[];
layout(location = 1) in vec4 vsColorOpacity[];
layout(location = 2) flat in int vsSegment[];
layout(location = 0) out vec4 tcsPositionWidth[];
layout(location = 1) out vec4 tcsColorOpacity[];
layout(location = 2) flat out int tcsSegment[];

vec2 toTessellationPixels(vec4 clip) { return (clip.xy / clip.w * 0.5 + 0.5) * frame.tessellationViewport; }

void main() {
    tcsPositionWidth[gl_InvocationID] = vsPositionWidth[gl_InvocationID];
    tcsColorOpacity[gl_InvocationID] = vsColorOpacity[gl_InvocationID];
    tcsSegment[gl_InvocationID] = vsSegment[gl_InvocationID];
    if (gl_InvocationID != 0) return;

    vec3 c0 = vsPositionWidth[0].xyz, c1 = vsPositionWidth[1].xyz;
    vec3 c2 = vsPositionWidth[2].xyz, c3 = vsPositionWidth[3].xyz;
    // The span's Bezier control polygon contains the curve (convex hull
    // property), so it bounds both culling and projected length.
    vec3 hull[4] = vec3[4](c1, c1 + (c2 - c0) / 6.0, c2 - (c3 - c1) / 6.0, c2);
    float halfWidth = 0.5 * max(max(vsPositionWidth[1].w, vsPositionWidth[2].w),
                                max(vsPositionWidth[0].w, vsPositionWidth[3].w));

    vec4 clip[4];
    for (int i = 0; i < 4; ++i) clip[i] = frame.viewProjection * vec4(hull[i], 1.0);

    // Outside one frustum plane with every hull point -> culled. The margin is
    // the ribbon's half width on screen (at least half the minimum drawn
    // width, plus a pixel), turned into clip units at that point's depth.
    bool culled = false;
    for (int axis = 0; axis < 3 && !culled; ++axis) {
        bool allBelow = true, allAbove = true;
        for (int i = 0; i < 4; ++i) {
            float w = max(abs(clip[i].w), 1e-12);
            float marginPixels = max(halfWidth * frame.pixelsPerUnit / w, 0.5 * frame.minPixelWidth) + 1.0;
            float extent = axis == 1 ? frame.viewportSize.y : frame.viewportSize.x;
            float margin = marginPixels * 2.0 / extent * w;
            allBelow = allBelow && clip[i][axis] < -clip[i].w - margin;
            allAbove = allAbove && clip[i][axis] > clip[i].w + margin;
        }
        culled = allBelow || allAbove;
    }

    vec4 tessellationClip[4];
    for (int i = 0; i < 4; ++i) tessellationClip[i] = frame.tessellationViewProjection * vec4(hull[i], 1.0);
    float level = frame.maxSegmentsPerSpan;
    bool inFront = tessellationClip[0].w > 0.0 && tessellationClip[1].w > 0.0 && tessellationClip[2].w > 0.0 &&
                   tessellationClip[3].w > 0.0;
    if (inFront) {
        float pixels = 0.0;
        for (int i = 0; i < 3; ++i)
            pixels += distance(toTessellationPixels(tessellationClip[i]), toTessellationPixels(tessellationClip[i + 1]));
        level = clamp(ceil(pixels / frame.pixelsPerSegment), 1.0, frame.maxSegmentsPerSpan);
    }
    if (culled) level = 0.0;

    // Quad domain: u runs along the span (outer 1 and 3, inner 0), v across
    // the strand's width, one quad wide (outer 0 and 2, inner 1).
    gl_TessLevelOuter[0] = culled ? 0.0 : 1.0;
    gl_TessLevelOuter[1] = level;
    gl_TessLevelOuter[2] = culled ? 0.0 : 1.0;
    gl_TessLevelOuter[3] = level;
    gl_TessLevelInner[0] = level;
    gl_TessLevelInner[1] = 1.0;
}
