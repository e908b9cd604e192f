#version 450 core
#extension GL_GOOGLE_include_directive : require
// The compute rasteriser for thin strands (strandRaster=compute): one
// invocation a span does, in parallel, what strand.tesc, strand.tese,
// strand.geom and the rasteriser do for the hardware path, and appends each
// covered pixel's shaded fragment to that pixel's list, as
// strandFragmentList.frag does; fragmentListResolve.frag then sorts and
// composites every pixel (hdHair/gl/FragmentListPass.cpp). On llvmpipe the
// vertex, tessellation and geometry stages of a draw run on the one thread
// that issues it; compute workgroups run on every core.
//
// The span is cut as strand.tesc cuts it (strandTessellationLevel.glsl), its
// points are the ribbon's (strandRibbonPoint.glsl: drawn width and the
// sub-pixel coverage rule, alpha = opacity x true width / drawn width), and
// each segment's quad is the two triangles strand.geom's strip makes. The
// triangles are clipped at the near plane (clipEdgeAtNear) and scan-converted at pixel
// centres with a tie-breaking rule that gives a pixel on a shared edge to
// one triangle only; attributes are interpolated perspective-correctly and
// window depth linearly in screen space, as GL's rasteriser does
// (OpenGL 4.5 core, sections 14.6.1 and 14.6.3). Fragments behind the
// frame's depth (opaque meshes drawn before) are rejected, as the list
// pass's early depth test (LEQUAL) does.
#define HDHAIR_COMPUTE_RASTER 1
#include "include/shadingFeatures.glsl"
#include "include/frameUniforms.glsl"
#include "include/lights.glsl"
#include "include/kajiyaKay.glsl"
#include "include/marschner.glsl"
#include "include/marschnerAnalytic.glsl"
#include "include/dualScattering.glsl"
#include "include/catmullRom.glsl"
#include "include/strandPoint.glsl"
#include "include/strandGeometry.glsl"
#include "include/hairMaterials.glsl"
#include "include/shadowFragmentLists.glsl"
#include "include/shadows.glsl"
#include "include/srbfLighting.glsl"
#include "include/strandShading.glsl"
#include "include/strandTessellationLevel.glsl"
#include "include/strandRibbonPoint.glsl"
#define HDHAIR_FRAGMENT_LIST_APPEND 1
#include "include/fragmentLists.glsl"

layout(local_size_x = 32) in;

// The frame's depth buffer: what opaque geometry drawn before left.
layout(binding = 9) uniform sampler2D frameDepth;
layout(location = 0) uniform uint rangeFirst;
layout(location = 1) uniform uint rangeCount;

// A corner of a segment's quad, with what strand.geom gives the rasteriser.
struct RasterVertex {
    vec4 clip;
    vec3 world;
    vec3 tangent;
    vec4 colorAlpha;
    float spanU;
    vec3 centre;
#ifdef HDHAIR_VERTEX_SHADOWS
    vec4 transmittance[HDHAIR_VERTEX_SHADOW_VECTORS];
#endif
};

RasterVertex mixVertex(RasterVertex a, RasterVertex b, float t) {
    RasterVertex v;
    v.clip = mix(a.clip, b.clip, t);
    v.world = mix(a.world, b.world, t);
    v.tangent = mix(a.tangent, b.tangent, t);
    v.colorAlpha = mix(a.colorAlpha, b.colorAlpha, t);
    v.spanU = mix(a.spanU, b.spanU, t);
    v.centre = mix(a.centre, b.centre, t);
#ifdef HDHAIR_VERTEX_SHADOWS
    for (int i = 0; i < HDHAIR_VERTEX_SHADOW_VECTORS; ++i) v.transmittance[i] = mix(a.transmittance[i], b.transmittance[i], t);
#endif
    return v;
}

// Window coordinates: pixels, and depth in [0, 1] (the default depth range).
// Positions snapped to 1/256 pixel, the subpixel precision llvmpipe rasterises with.
vec3 toWindow(vec4 clip) {
    vec2 pixels = (clip.xy / clip.w * 0.5 + 0.5) * frame.viewportSize;
    return vec3(round(pixels * 256.0) / 256.0, clip.z / clip.w * 0.5 + 0.5);
}

float edgeFunction(vec2 a, vec2 b, vec2 p) { return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x); }

// Whether a pixel centre exactly on the edge a -> b of a counter-clockwise
// triangle belongs to it: the two triangles sharing the edge see it in
// opposite directions, so exactly one of them takes the pixel.
bool ownsEdge(vec2 a, vec2 b) { return a.y < b.y || (a.y == b.y && a.x > b.x); }

void appendFragment(ivec2 pixel, float depth, RasterVertex a, RasterVertex b, RasterVertex c, vec3 perspective,
                    ivec4 ids) {
    vec4 colorAlpha = perspective.x * a.colorAlpha + perspective.y * b.colorAlpha + perspective.z * c.colorAlpha;
    float alpha = colorAlpha.a;
    if (alpha <= 0.0) return;
    if (depth > texelFetch(frameDepth, pixel, 0).r) return;
    vec3 world = perspective.x * a.world + perspective.y * b.world + perspective.z * c.world;
    vec3 tangent = perspective.x * a.tangent + perspective.y * b.tangent + perspective.z * c.tangent;
    vec3 centre = perspective.x * a.centre + perspective.y * b.centre + perspective.z * c.centre;
    float spanU = perspective.x * a.spanU + perspective.y * b.spanU + perspective.z * c.spanU;
#ifdef HDHAIR_VERTEX_SHADOWS
    for (int i = 0; i < HDHAIR_VERTEX_SHADOW_VECTORS; ++i)
        vertexTransmittance[i] =
            perspective.x * a.transmittance[i] + perspective.y * b.transmittance[i] + perspective.z * c.transmittance[i];
#endif
    vec3 radiance = strandRadiance(world, centre, tangent, colorAlpha.rgb, ids.z, ids.w, spanU);
    appendFragmentNode(pixel, vec4(radiance * alpha, alpha), depth, ids.w);
}

// Scan-converts a triangle wholly in front of the near plane.
void rasterizeTriangle(RasterVertex a, RasterVertex b, RasterVertex c, ivec4 ids) {
    vec3 wa = toWindow(a.clip), wb = toWindow(b.clip), wc = toWindow(c.clip);
    float area = edgeFunction(wa.xy, wb.xy, wc.xy);
    if (!(abs(area) > 0.0)) return;  // degenerate (or not finite): covers no pixel centre
    if (area < 0.0) {
        RasterVertex swapped = b;
        b = c;
        c = swapped;
        vec3 w = wb;
        wb = wc;
        wc = w;
        area = -area;
    }
    vec2 lower = min(wa.xy, min(wb.xy, wc.xy)), upper = max(wa.xy, max(wb.xy, wc.xy));
    // Rows whose pixel centres y + 0.5 lie inside [lower.y, upper.y], within the viewport.
    int firstRow = int(max(ceil(lower.y - 0.5), 0.0));
    int lastRow = int(min(floor(upper.y - 0.5), frame.viewportSize.y - 1.0));
    bool ownsA = ownsEdge(wb.xy, wc.xy), ownsB = ownsEdge(wc.xy, wa.xy), ownsC = ownsEdge(wa.xy, wb.xy);
    vec3 inverseW = vec3(1.0 / a.clip.w, 1.0 / b.clip.w, 1.0 / c.clip.w);
    // Each edge function is linear along a row: e(x) = slope * x + e(0).
    // Its half-plane bounds the row's span of x; the span is then walked
    // with the exact test, a pixel wider on each side, so that a thin
    // diagonal sliver costs the pixels it covers rather than its bounding box.
    vec2 edgeStart[3] = vec2[3](wb.xy, wc.xy, wa.xy), edgeEnd[3] = vec2[3](wc.xy, wa.xy, wb.xy);
    for (int y = firstRow; y <= lastRow; ++y) {
        float py = float(y) + 0.5;
        float left = lower.x, right = upper.x;
        for (int i = 0; i < 3; ++i) {
            float slope = -(edgeEnd[i].y - edgeStart[i].y);
            float atZero = edgeFunction(edgeStart[i], edgeEnd[i], vec2(0.0, py));
            if (slope > 0.0) left = max(left, -atZero / slope);
            else if (slope < 0.0) right = min(right, -atZero / slope);
        }
        int firstColumn = int(max(ceil(left - 0.5) - 1.0, max(ceil(lower.x - 0.5), 0.0)));
        int lastColumn = int(min(floor(right - 0.5) + 1.0, min(floor(upper.x - 0.5), frame.viewportSize.x - 1.0)));
        for (int x = firstColumn; x <= lastColumn; ++x) {
            vec2 p = vec2(float(x) + 0.5, py);
            vec3 e = vec3(edgeFunction(wb.xy, wc.xy, p), edgeFunction(wc.xy, wa.xy, p), edgeFunction(wa.xy, wb.xy, p));
            if (e.x < 0.0 || e.y < 0.0 || e.z < 0.0) continue;
            if ((e.x == 0.0 && !ownsA) || (e.y == 0.0 && !ownsB) || (e.z == 0.0 && !ownsC)) continue;
            vec3 screen = e / area;
            float depth = dot(screen, vec3(wa.z, wb.z, wc.z));
            if (depth < 0.0 || depth > 1.0) continue;  // beyond the far plane
            vec3 perspective = screen * inverseW;
            perspective /= perspective.x + perspective.y + perspective.z;
            appendFragment(ivec2(x, y), depth, a, b, c, perspective, ids);
        }
    }
}

// GL's near plane: z >= -w.
float nearDistance(RasterVertex v) { return v.clip.z + v.clip.w; }

// Clips one long edge of a segment's quad (from `start` to `end`, the same
// edge of the ribbon at the segment's two ends) at the near plane, moving
// the end behind it onto it: GL clips in clip space, where every attribute
// is linear along the edge as it is here. Returns false when both ends are
// behind. A quad whose near plane crosses one of its short edges loses the
// sliver beyond the moved corner, under half the strand's width at the
// plane, where GL would keep a pentagon; it still draws everything more
// than that in front of the plane. Per edge rather than per triangle: every
// branch of a shader runs on llvmpipe, taken or not (masked), and clipping
// triangles one by one cost each span about a fifth of its time.
bool clipEdgeAtNear(inout RasterVertex start, inout RasterVertex end) {
    float ds = nearDistance(start), de = nearDistance(end);
    if (ds < 0.0 && de < 0.0) return false;
    if (ds < 0.0) start = mixVertex(start, end, ds / (ds - de));
    else if (de < 0.0) end = mixVertex(start, end, ds / (ds - de));
    return true;
}

// The two corners of the ribbon at a tessellated point (strand.geom's edges 0 and 1).
void ribbonCorners(vec4 positionWidth[4], vec4 colorOpacity[4], float u, out RasterVertex edge0,
                   out RasterVertex edge1) {
    RibbonPoint ribbon = strandRibbonPoint(evaluateStrandPoint(positionWidth, colorOpacity, u));
    RasterVertex v;
    v.tangent = ribbon.tangent;
    v.colorAlpha = ribbon.colorAlpha;
    v.spanU = u;
    v.centre = ribbon.centre;
#ifdef HDHAIR_VERTEX_SHADOWS
    vertexShadowTransmittance(ribbon.centre, v.transmittance);
#endif
    edge0 = v;
    edge1 = v;
    edge0.world = ribbon.centre - 0.5 * ribbon.across;
    edge1.world = ribbon.centre + 0.5 * ribbon.across;
    edge0.clip = frame.viewProjection * vec4(edge0.world, 1.0);
    edge1.clip = frame.viewProjection * vec4(edge1.world, 1.0);
}

void main() {
    uint index = gl_GlobalInvocationID.x;
    if (index >= rangeCount) return;
    int segment = int(rangeFirst + index);
    vec4 positionWidth[4], colorOpacity[4];
    segmentControls(uint(segment), positionWidth, colorOpacity);
    float level = strandTessellationLevel(positionWidth, colorOpacity);
    if (level <= 0.0) return;
    ivec4 ids = segmentIds(segment);
    // Isolines with equal spacing: points at u = i / level.
    int segments = int(level);
    RasterVertex previous0, previous1;
    ribbonCorners(positionWidth, colorOpacity, 0.0, previous0, previous1);
    for (int i = 1; i <= segments; ++i) {
        RasterVertex next0, next1;
        ribbonCorners(positionWidth, colorOpacity, float(i) / level, next0, next1);
        // strand.geom's strip: (end 0 edge 0, end 0 edge 1, end 1 edge 0),
        // then (end 1 edge 0, end 0 edge 1, end 1 edge 1); one call site, as
        // llvmpipe inlines each.
        RasterVertex start0 = previous0, start1 = previous1, end0 = next0, end1 = next1;
        if (clipEdgeAtNear(start0, end0) && clipEdgeAtNear(start1, end1)) {
            RasterVertex a = start0, b = start1, c = end0;
            for (int triangle = 0; triangle < 2; ++triangle) {
                rasterizeTriangle(a, b, c, ids);
                a = end0;
                c = end1;
            }
        }
        previous0 = next0;
        previous1 = next1;
    }
}
