// A point of a Catmull-Rom span at u in [0, 1], from its four control points
// (position and width, colour and opacity): what strand.tese evaluates at
// each tessellated point, and strandChord.vert at a span's two ends. Needs
// catmullRom.glsl.
struct StrandPoint {
    vec4 positionWidth;
    vec3 tangent;  // unit length
    vec4 shade;    // colour and opacity, as interpolated (callers clamp)
};

StrandPoint evaluateStrandPoint(vec4 positionWidth[4], vec4 colorOpacity[4], float u) {
    vec4 w = catmullRomWeights(u);
    vec4 dw = catmullRomDerivativeWeights(u);

    StrandPoint point;
    point.positionWidth = vec4(0.0);
    point.tangent = vec3(0.0);
    point.shade = vec4(0.0);
    for (int i = 0; i < 4; ++i) {
        point.positionWidth += w[i] * positionWidth[i];
        point.tangent += dw[i] * positionWidth[i].xyz;
        point.shade += w[i] * colorOpacity[i];
    }
    // A zero-length derivative (coincident control points) falls back to the
    // chord, then to any axis: the ribbon must stay well defined.
    if (dot(point.tangent, point.tangent) < 1e-20) point.tangent = positionWidth[2].xyz - positionWidth[1].xyz;
    if (dot(point.tangent, point.tangent) < 1e-20) point.tangent = vec3(0.0, 1.0, 0.0);
    point.tangent = normalize(point.tangent);
    return point;
}
