// Strand lines (HDHAIR_STRAND_LINES, the light views' shadowStrandLines when
// no strand is over 1.5 texels wide there): no geometry shader; a span's
// polyline is rasterised as one-pixel lines, with the fragment stage's
// inputs written by the last vertex stage (strand.tese, or strandChord.vert
// for spans left one segment). A line lights one pixel per step along its
// major axis: m pixels per pixel of its length, m = max(|dx|, |dy|) /
// |(dx, dy)| of its screen direction (1 along an axis, 1/sqrt(2)
// diagonally), where a ribbon of the true width covers `width in pixels` of
// area. So each pixel takes alpha opacity x width in pixels / m, and the
// opacity the pixels sum is the ribbon's at every angle: above 1 for a
// strand wider than the line (RenderPlan.cpp's kMaxStrandLineTexels bounds
// how much wider). Needs frameUniforms.glsl and strandPoint.glsl. The light
// views' compute rasteriser (HDHAIR_COMPUTE_RASTER, lightViewLines.glsl)
// takes the same vertices from strandLineVertex.

// A line's vertex: where it lies and the alpha it carries.
struct StrandLineVertex {
    vec4 clip;
    vec3 world;
    vec4 colorAlpha;  // displayColor, opacity x coverage
};

StrandLineVertex strandLineVertex(StrandPoint point) {
    vec3 position = point.positionWidth.xyz;
    vec4 clip = frame.viewProjection * vec4(position, 1.0);
    float clipW = max(abs(clip.w), 1e-12);
    // The tangent's screen direction: d(clip.xy / clip.w) along it, in
    // pixels (the common factor 1 / w^2 dropped).
    vec4 clipTangent = frame.viewProjection * vec4(point.tangent, 0.0);
    vec2 screen = (clipTangent.xy * clip.w - clip.xy * clipTangent.w) * frame.viewportSize;
    float screenLength = length(screen);
    // End-on (no screen direction) the line is a point: m = 1.
    float m = screenLength > 0.0 ? clamp(max(abs(screen.x), abs(screen.y)) / screenLength, 0.70710678, 1.0) : 1.0;
    // Cubic interpolation can overshoot: widths, colours and opacities are clamped.
    float widthPixels = max(point.positionWidth.w, 0.0) * frame.pixelsPerUnit / clipW;
    float opacity = clamp(point.shade.a, 0.0, 1.0);
    StrandLineVertex vertex;
    vertex.clip = clip;
    vertex.world = position;
    vertex.colorAlpha = vec4(max(point.shade.rgb, vec3(0.0)), opacity * widthPixels / m);
    return vertex;
}

#ifndef HDHAIR_COMPUTE_RASTER
// What strand.geom hands the fragment stage, at its locations.
layout(location = 0) out vec3 worldPosition;
layout(location = 1) out vec3 worldTangent;
layout(location = 2) out vec4 colorAlpha;  // displayColor, opacity x coverage
layout(location = 3) flat out ivec4 ids;   // primId, elementId, material, segment
layout(location = 4) out float spanU;
layout(location = 5) out vec3 strandCentre;

// Writes `point` (at u of its span, with `pointIds`) as a line's vertex.
void emitStrandLinePoint(StrandPoint point, ivec4 pointIds, float u) {
    StrandLineVertex vertex = strandLineVertex(point);
    worldPosition = vertex.world;
    strandCentre = vertex.world;
    worldTangent = point.tangent;
    colorAlpha = vertex.colorAlpha;
    ids = pointIds;
    spanU = u;
    gl_Position = vertex.clip;
}
#endif
