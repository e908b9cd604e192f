// Uniform Catmull-Rom (tension 0.5) weights for the span from C1 (u = 0) to
// C2 (u = 1). Must match hdHair/curves/CatmullRomEvaluation.h.
vec4 catmullRomWeights(float u) {
    float u2 = u * u, u3 = u2 * u;
    return vec4(-0.5 * u3 + u2 - 0.5 * u,
                1.5 * u3 - 2.5 * u2 + 1.0,
                -1.5 * u3 + 2.0 * u2 + 0.5 * u,
                0.5 * u3 - 0.5 * u2);
}

// d/du of catmullRomWeights.
vec4 catmullRomDerivativeWeights(float u) {
    float u2 = u * u;
    return vec4(-1.5 * u2 + 2.0 * u - 0.5,
                4.5 * u2 - 5.0 * u,
                -4.5 * u2 + 4.0 * u + 0.5,
                1.5 * u2 - u);
}
