// Marschner hair scattering (Marschner et al. 2003, "Light Scattering from
// Human Hair Fibers") with d'Eon et al. 2011's energy-conserving longitudinal
// term, the azimuthal part read from per-material tables. Must match
// hdHair/shading/Marschner.h (the model, symbols, equation numbers) and
// hdHair/shading/MarschnerTables.h (evaluateMarschnerTabled), formula for
// formula.
//
// tables: sampler2DArray holding buildMarschnerTables() output, 2 layers a
//   material starting at baseLayer,
//   GL_RGBA16F, 64 x 64, GL_LINEAR, no mipmaps, GL_CLAMP_TO_EDGE;
//   layer 0: rgb = N_TT, a = N_R;  layer 1: rgb = N_TRT (caustic treated);
//   s = phi / pi (phi = |phi_r - phi_i| in [0, pi]), t = cos(theta_r).
// alpha: (alpha_R, alpha_TT, alpha_TRT) cuticle tilts, radians.
// beta:  (beta_R, beta_TT, beta_TRT) longitudinal widths (std. dev. in theta_h), radians.
// t: tangent (root to tip), wi: towards the light, wo: towards the eye; need
// not be normalised. Returns f_p = S_p cos(theta_i): multiply by the light's
// irradiance (like kajiyaKay()'s terms).
struct MarschnerLobes {
    vec3 R;
    vec3 TT;
    vec3 TRT;
};

const float MARSCHNER_PI = 3.14159265358979323846;

// log I0(x), x >= 0: series below 12, asymptotic expansion above
// (Marschner.cpp logBesselI0; 24 terms reach 1e-7 relative at x = 12).
float marschnerLogI0(float x) {
    if (x > 12.0) {
        float inverse = 1.0 / x;
        return x - 0.5 * log(2.0 * MARSCHNER_PI * x) + log(1.0 + inverse * (0.125 + inverse * 0.0703125));
    }
    float quarterSquare = 0.25 * x * x, term = 1.0, sum = 1.0;
    for (int k = 1; k < 24; ++k) {
        term *= quarterSquare / float(k * k);
        sum += term;
    }
    return log(sum);
}

// d'Eon's M(theta_i, theta_r - 2 alpha) with v = (2 beta)^2 (marschnerLongitudinal).
float marschnerLongitudinal(float sinThetaI, float cosThetaI, float sinThetaR, float cosThetaR, float alpha,
                            float beta) {
    float b = clamp(abs(beta), 0.5 * MARSCHNER_PI / 180.0, 3.0);
    float v = 4.0 * b * b;
    float c2 = cos(2.0 * alpha), s2 = sin(2.0 * alpha);
    float sinR = sinThetaR * c2 - cosThetaR * s2;
    float cosR = abs(cosThetaR * c2 + sinThetaR * s2);
    float a = cosThetaI * cosR / v, bb = sinThetaI * sinR / v;
    float m;
    if (v <= 0.1) {
        m = exp(marschnerLogI0(a) - bb - 1.0 / v - log(v));
    } else {
        m = exp(-bb + marschnerLogI0(a)) / (2.0 * v * sinh(1.0 / v));
    }
    return (isnan(m) || isinf(m)) ? 0.0 : max(m, 0.0);
}

vec3 marschnerSafeNormalize(vec3 v) {
    float len = length(v);
    return (len > 1e-20 && !isinf(len) && !isnan(len)) ? v / len : vec3(0.0);
}

// The angles of a configuration (Marschner.cpp marschnerAngles): zero vectors
// count as perpendicular to everything, a direction along t has phi = 0.
struct MarschnerAngles {
    float sinThetaI, cosThetaI, sinThetaR, cosThetaR;
    float phi;  // |phi_r - phi_i| in [0, pi]
};

MarschnerAngles marschnerAngles(vec3 t, vec3 wi, vec3 wo) {
    vec3 tn = marschnerSafeNormalize(t), inDir = marschnerSafeNormalize(wi), outDir = marschnerSafeNormalize(wo);
    MarschnerAngles angles;
    // sin(theta) = t . w; theta from the normal plane.
    angles.sinThetaI = clamp(dot(tn, inDir), -1.0, 1.0);
    angles.sinThetaR = clamp(dot(tn, outDir), -1.0, 1.0);
    angles.cosThetaI = sqrt(max(0.0, 1.0 - angles.sinThetaI * angles.sinThetaI));
    angles.cosThetaR = sqrt(max(0.0, 1.0 - angles.sinThetaR * angles.sinThetaR));
    // phi: angle between the projections onto the normal plane; 0 when either is degenerate.
    vec3 pi = inDir - angles.sinThetaI * tn, po = outDir - angles.sinThetaR * tn;
    float lengths = length(pi) * length(po);
    angles.phi = lengths > 1e-12 ? abs(atan(length(cross(pi, po)), dot(pi, po))) : 0.0;
    return angles;
}

// f_p = M_p N_p for the three lobes (Marschner.cpp combineMarschnerLobes).
MarschnerLobes marschnerCombineLobes(MarschnerAngles angles, vec3 nR, vec3 nTT, vec3 nTRT, vec3 alpha, vec3 beta) {
    MarschnerLobes lobes;
    lobes.R = max(nR, vec3(0.0)) * marschnerLongitudinal(angles.sinThetaI, angles.cosThetaI, angles.sinThetaR,
                                                         angles.cosThetaR, alpha.x, beta.x);
    lobes.TT = max(nTT, vec3(0.0)) * marschnerLongitudinal(angles.sinThetaI, angles.cosThetaI, angles.sinThetaR,
                                                           angles.cosThetaR, alpha.y, beta.y);
    lobes.TRT = max(nTRT, vec3(0.0)) * marschnerLongitudinal(angles.sinThetaI, angles.cosThetaI, angles.sinThetaR,
                                                             angles.cosThetaR, alpha.z, beta.z);
    return lobes;
}

MarschnerLobes marschnerTabledLobes(vec3 t, vec3 wi, vec3 wo, sampler2DArray tables, float baseLayer, vec3 alpha,
                                    vec3 beta) {
    MarschnerAngles angles = marschnerAngles(t, wi, wo);
    // N_p(phi, cos theta_r): two bilinear fetches at (phi / pi, cos theta_r).
    vec2 st = vec2(clamp(angles.phi / MARSCHNER_PI, 0.0, 1.0), angles.cosThetaR);
    vec4 layer0 = texture(tables, vec3(st, baseLayer));
    vec4 layer1 = texture(tables, vec3(st, baseLayer + 1.0));
    return marschnerCombineLobes(angles, vec3(layer0.a), layer0.rgb, layer1.rgb, alpha, beta);
}

// R + TT + TRT: the radiance towards wo per unit irradiance from wi.
vec3 marschnerTabled(vec3 t, vec3 wi, vec3 wo, sampler2DArray tables, float baseLayer, vec3 alpha, vec3 beta) {
    MarschnerLobes lobes = marschnerTabledLobes(t, wi, wo, tables, baseLayer, alpha, beta);
    return lobes.R + lobes.TT + lobes.TRT;
}
