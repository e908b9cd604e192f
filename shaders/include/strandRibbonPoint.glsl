// A point of a strand's camera-facing ribbon, from the centre-line point
// strandPoint.glsl evaluates: the vector across the ribbon (a world-space
// diameter, perpendicular to both the tangent and the view) and the colour
// and alpha the point carries. strand.tese emits these for the hardware
// rasteriser and strandRaster.comp rasterises them itself, so both paths
// draw the same ribbon.
//
// Sub-pixel coverage (Svoboda 2012, section 1.2.3): a strand whose projected
// width is below frame.minPixelWidth is drawn that wide instead, with its
// alpha scaled by true width / drawn width, so thin hair fades with distance
// instead of breaking up into dashes or vanishing.
// Needs frameUniforms.glsl and strandPoint.glsl; with HDHAIR_VERTEX_SHADOWS
// also lights.glsl, shadowFragmentLists.glsl and shadows.glsl.
struct RibbonPoint {
    vec3 centre;      // the centre line at u
    vec3 across;      // from one edge of the ribbon to the other
    vec3 tangent;
    vec4 colorAlpha;  // displayColor, opacity x coverage
};

RibbonPoint strandRibbonPoint(StrandPoint point) {
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
    RibbonPoint ribbon;
    ribbon.centre = point.positionWidth.xyz;
    ribbon.across = side * drawnWidth;
    ribbon.tangent = point.tangent;
    ribbon.colorAlpha = vec4(max(point.shade.rgb, vec3(0.0)), opacity);
    return ribbon;
}

#ifdef HDHAIR_VERTEX_SHADOWS
// Vertex shadows (shadowSampling=vertex): the pass's first
// HDHAIR_VERTEX_SHADOWS lights' transmittance at a centre-line point, 4 a
// vec4, the rest 1; strandShading.glsl interpolates them along the segment.
void vertexShadowTransmittance(vec3 centre, out vec4 transmittance[HDHAIR_VERTEX_SHADOW_VECTORS]) {
    for (int v = 0; v < HDHAIR_VERTEX_SHADOW_VECTORS; ++v) transmittance[v] = vec4(1.0);
    for (int i = 0; i < HDHAIR_VERTEX_SHADOWS; ++i)
        transmittance[i / 4][i % 4] =
            isSrbfLight(i) ? srbfShadowTransmittance(i, centre) : shadowTransmittance(i, centre);
}
#endif
