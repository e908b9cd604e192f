// How finely strand.tesc cuts a Catmull-Rom span, as a function of its four
// control points alone, so that lightViewLevels.comp can ask the same of
// every span of a light view (LightViewSpans.h): by default (screenError) as
// few segments as keep the polyline within frame.tessellationTolerance
// pixels of the curve, so a straight span is one segment however long it is
// and only bends cost segments; or (projectedLength) one segment every
// pixelsPerSegment projected pixels; never more than maxSegmentsPerSpan.
// Both follow projected size in the pass's own view: strands far away or
// seen end-on cost few, and a light view cuts by its map's texels
// (lightViewFrameUniforms, hdHair/render/ShadowPassUniforms.cpp). Vertex
// shadows cut the camera's long spans finer (below). Culling is per view:
// a span wholly outside this pass's frustum gets level 0. Needs
// frameUniforms.glsl.

vec2 toPixels(vec4 clip) { return (clip.xy / clip.w * 0.5 + 0.5) * frame.viewportSize; }

// The largest factor by which the pass's view stretches a world-space
// length anywhere in the convex hull whose clip positions are `clip` (all in
// front: w > 0), in pixels a world unit. At a point, pixels move by
// J = diag(viewport / 2) * (A_xy - ndc (x) A_w) / w for a world step, A the
// view-projection's 3x3 rows. Over the hull w is smallest at a vertex (it is
// linear) and ndc stays in the box of the vertices' ndc (a linear-fractional
// map of a convex polytope), and |J| is convex in ndc: its largest value is at
// a corner of that box, over the least w.
float hullStretch(vec4 clip[4]) {
    mat4 m = frame.viewProjection;
    vec3 rowX = vec3(m[0][0], m[1][0], m[2][0]), rowY = vec3(m[0][1], m[1][1], m[2][1]);
    vec3 rowW = vec3(m[0][3], m[1][3], m[2][3]);
    vec2 halfViewport = 0.5 * frame.viewportSize;
    float minW = clip[0].w;
    vec2 ndcMin = clip[0].xy / clip[0].w, ndcMax = ndcMin;
    for (int i = 1; i < 4; ++i) {
        minW = min(minW, clip[i].w);
        ndcMin = min(ndcMin, clip[i].xy / clip[i].w);
        ndcMax = max(ndcMax, clip[i].xy / clip[i].w);
    }
    float stretch = 0.0;
    for (int corner = 0; corner < 4; ++corner) {
        vec2 ndc = vec2((corner & 1) != 0 ? ndcMax.x : ndcMin.x, (corner & 2) != 0 ? ndcMax.y : ndcMin.y);
        vec3 jx = halfViewport.x * (rowX - ndc.x * rowW), jy = halfViewport.y * (rowY - ndc.y * rowW);
        // Spectral norm of the 2x3 matrix (jx; jy): the larger eigenvalue of
        // its 2x2 Gram matrix.
        float a = dot(jx, jx), b = dot(jx, jy), c = dot(jy, jy);
        float largest = 0.5 * (a + c) + sqrt(0.25 * (a - c) * (a - c) + b * b);
        stretch = max(stretch, sqrt(largest));
    }
    return stretch / minW;
}

// The most linear interpolation of colour and opacity along a segment may
// stray from their cubic: an eighth of an 8-bit step.
const float kAttributeTolerance = 1.0 / 2048.0;

// Segments that keep the span's polyline within frame.tessellationTolerance
// pixels of the curve. A chord of a curve over a parameter step h strays at
// most h^2 / 8 * max|C''| from it; a cubic Bezier's C''(t) = 6((1 - t) d0 + t d1)
// with d0 = B0 - 2 B1 + B2 and d1 = B1 - 2 B2 + B3, so n equal steps stray at
// most 0.75 max(|d0|, |d1|) / n^2 world units, at most `stretch` pixels each.
// The world-unit bound holds in every direction, depth included: a light
// view's polyline stays within the tolerance of a texel's world size of the
// curve along the light too, where its map's depths are (shadows.glsl's bias
// relies on it, and the camera's points lie on the same curve).
float screenErrorLevel(vec3 hull[4], float widthHull[4], vec4 clip[4]) {
    // The ribbon's edges lie half a width to either side of the centre line:
    // their chords stray by at most the centre's error plus half the width's.
    float bend = max(length(hull[0] - 2.0 * hull[1] + hull[2]) + 0.5 * abs(widthHull[0] - 2.0 * widthHull[1] + widthHull[2]),
                     length(hull[1] - 2.0 * hull[2] + hull[3]) + 0.5 * abs(widthHull[1] - 2.0 * widthHull[2] + widthHull[3]));
    return ceil(sqrt(0.75 * bend * hullStretch(clip) / frame.tessellationTolerance));
}

// The segments span (positionWidth, colorOpacity: its four control points)
// is cut into in this pass's view; 0: culled.
float strandTessellationLevel(vec4 positionWidth[4], vec4 colorOpacity[4]) {
    vec3 c0 = positionWidth[0].xyz, c1 = positionWidth[1].xyz;
    vec3 c2 = positionWidth[2].xyz, c3 = positionWidth[3].xyz;
    // The span's Bezier control polygon contains the curve (convex hull
    // property), so it bounds both culling and projected length.
    vec3 hull[4] = vec3[4](c1, c1 + (c2 - c0) / 6.0, c2 - (c3 - c1) / 6.0, c2);
    float w0 = positionWidth[0].w, w1 = positionWidth[1].w, w2 = positionWidth[2].w, w3 = positionWidth[3].w;
    float widthHull[4] = float[4](w1, w1 + (w2 - w0) / 6.0, w2 - (w3 - w1) / 6.0, w2);
    float halfWidth = 0.5 * max(max(positionWidth[1].w, positionWidth[2].w),
                                max(positionWidth[0].w, positionWidth[3].w));

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

    float level = frame.maxSegmentsPerSpan;
    bool inFront = clip[0].w > 0.0 && clip[1].w > 0.0 && clip[2].w > 0.0 && clip[3].w > 0.0;
    if (inFront) {
        float pixels = 0.0;
        for (int i = 0; i < 3; ++i)
            pixels += distance(toPixels(clip[i]), toPixels(clip[i + 1]));
        if (frame.tessellationTolerance > 0.0) {
            // Colour and opacity are interpolated linearly between the
            // polyline's vertices: cut finely enough that they stay within
            // kAttributeTolerance of their cubic, but never finer than a
            // segment a pixel, where nothing finer could show.
            // Measured in linear Rec.709, as authored: the same levels in
            // every rendering space.
            vec4 a[4];
            for (int i = 0; i < 4; ++i) a[i] = vec4(frame.colorToRec709 * colorOpacity[i].rgb, colorOpacity[i].a);
            vec4 a0 = a[0], a1 = a[1], a2 = a[2], a3 = a[3];
            vec4 attributeHull[4] = vec4[4](a1, a1 + (a2 - a0) / 6.0, a2 - (a3 - a1) / 6.0, a2);
            vec4 d0 = abs(attributeHull[0] - 2.0 * attributeHull[1] + attributeHull[2]);
            vec4 d1 = abs(attributeHull[1] - 2.0 * attributeHull[2] + attributeHull[3]);
            vec4 d = max(d0, d1);
            float attributeBend = max(max(d.r, d.g), max(d.b, d.a));
            float attributeLevel = min(ceil(sqrt(0.75 * attributeBend / kAttributeTolerance)), ceil(pixels));
            level = max(screenErrorLevel(hull, widthHull, clip), attributeLevel);
        } else {
            level = ceil(pixels / frame.pixelsPerSegment);
        }
        level = clamp(level, 1.0, frame.maxSegmentsPerSpan);
        // Vertex shadows: no segment longer than frame.shadowSegmentLength,
        // bounded by the control polygon's length, which bounds the span's;
        // beyond maxSegmentsPerSpan if need be, up to 64 (the least
        // GL_MAX_TESS_GEN_LEVEL GL allows).
        if (frame.shadowSegmentLength > 0.0) {
            float polygon = distance(hull[0], hull[1]) + distance(hull[1], hull[2]) + distance(hull[2], hull[3]);
            level = max(level, min(ceil(polygon / frame.shadowSegmentLength), 64.0));
        }
    }
    if (culled) level = 0.0;

    return culled ? 0.0 : level;
}
