// The light views' compute rasteriser for strand lines (strandRaster=auto or
// compute with shadowStrandLines=auto: hdHair/gl/LightViewRaster.h). One
// invocation a span does what strand.tesc, strand.tese (or strandChord.vert)
// and GL's line rasteriser do for the hardware path: the span is cut by
// strandTessellationLevel.glsl, its points carry strandLinePoint.glsl's
// alpha, and each segment lights one texel per texel centre its major axis
// passes (the "Bresenham" rule OpenGL 4.5 core, section 14.5.1, allows
// beside diamond-exit), half-open so that the segments of a polyline share
// no texel. Attributes are interpolated perspective-correctly (equation
// 14.7). Every texel found is handed to lightViewTexel, which the including
// shader defines. On llvmpipe the vertex and tessellation stages of a draw
// run on the one thread that issues it; compute workgroups run on every core.
// Needs frameUniforms.glsl, catmullRom.glsl, strandPoint.glsl,
// strandGeometry.glsl, strandTessellationLevel.glsl and strandLinePoint.glsl
// (under HDHAIR_COMPUTE_RASTER).

void lightViewTexel(ivec2 texel, vec3 world, float alpha);

// Moves the end of a -> b outside `distance` >= 0 (a clip-space plane,
// linear along the segment) onto it; false when both ends are outside.
bool clipLineAtPlane(inout StrandLineVertex a, inout StrandLineVertex b, float da, float db) {
    if (da < 0.0 && db < 0.0) return false;
    float t = da / (da - db);
    if (da < 0.0) {
        a.clip = mix(a.clip, b.clip, t);
        a.world = mix(a.world, b.world, t);
        a.colorAlpha = mix(a.colorAlpha, b.colorAlpha, t);
    } else if (db < 0.0) {
        b.clip = mix(a.clip, b.clip, t);
        b.world = mix(a.world, b.world, t);
        b.colorAlpha = mix(a.colorAlpha, b.colorAlpha, t);
    }
    return true;
}

void rasterizeLightViewLine(StrandLineVertex a, StrandLineVertex b) {
    // GL's near and far planes: -w <= z <= w.
    if (!clipLineAtPlane(a, b, a.clip.z + a.clip.w, b.clip.z + b.clip.w)) return;
    if (!clipLineAtPlane(a, b, a.clip.w - a.clip.z, b.clip.w - b.clip.z)) return;
    vec2 pa = (a.clip.xy / a.clip.w * 0.5 + 0.5) * frame.viewportSize;
    vec2 pb = (b.clip.xy / b.clip.w * 0.5 + 0.5) * frame.viewportSize;
    vec2 delta = pb - pa;
    // Not finite, or no length: no texel (as diamond-exit gives none).
    if (!(abs(delta.x) + abs(delta.y) > 0.0) || any(isinf(delta))) return;
    bool xMajor = abs(delta.x) >= abs(delta.y);
    float start = xMajor ? pa.x : pa.y, end = xMajor ? pb.x : pb.y;
    float minorStart = xMajor ? pa.y : pa.x, minorSlope = xMajor ? delta.y / delta.x : delta.x / delta.y;
    float majorSize = xMajor ? frame.viewportSize.x : frame.viewportSize.y;
    float minorSize = xMajor ? frame.viewportSize.y : frame.viewportSize.x;
    // Texel centres c + 0.5 from start (taken) to end (left to the next
    // segment), clamped to the viewport before conversion to int.
    float first = end > start ? ceil(start - 0.5) : floor(start - 0.5);
    float last = end > start ? ceil(end - 0.5) - 1.0 : floor(end - 0.5) + 1.0;
    // Taken in either direction, [lower, upper] is empty (lower > upper)
    // for a segment that passes no texel centre.
    float lower = clamp(end > start ? first : last, 0.0, majorSize);
    float upper = clamp(end > start ? last : first, -1.0, majorSize - 1.0);
    float inverseWa = 1.0 / a.clip.w, inverseWb = 1.0 / b.clip.w;
    for (int i = int(lower); i <= int(upper); ++i) {
        float t = (float(i) + 0.5 - start) / (end - start);
        float minor = minorStart + (float(i) + 0.5 - start) * minorSlope;
        if (!(minor >= 0.0 && minor < minorSize)) continue;
        // Perspective-correct: t in the screen, tp along the segment.
        float tp = t * inverseWb / mix(inverseWa, inverseWb, t);
        ivec2 texel = xMajor ? ivec2(i, int(minor)) : ivec2(int(minor), i);
        lightViewTexel(texel, mix(a.world, b.world, tp), mix(a.colorAlpha.a, b.colorAlpha.a, tp));
    }
}

// Rasterises span `segment` as a polyline of lines, cut as strand.tesc cuts it.
void rasterizeLightViewSpan(uint segment) {
    vec4 positionWidth[4], colorOpacity[4];
    segmentControls(segment, positionWidth, colorOpacity);
    float level = strandTessellationLevel(positionWidth, colorOpacity);
    if (level <= 0.0) return;
    int segments = int(level);
    StrandLineVertex previous = strandLineVertex(evaluateStrandPoint(positionWidth, colorOpacity, 0.0));
    for (int i = 1; i <= segments; ++i) {
        StrandLineVertex next = strandLineVertex(evaluateStrandPoint(positionWidth, colorOpacity, float(i) / level));
        rasterizeLightViewLine(previous, next);
        previous = next;
    }
}
