// Multiple scattering in hair by the dual scattering approximation (Zinke,
// Yuksel, Weber & Keyser 2008, §4-5; Ren et al. 2010 §3.2 under SRBF
// lights). Must match hdHair/shading/DualScattering.h
// (sampleDualScatteringTable, evaluateDualScattering,
// dualScatteringUniformDome) formula for formula; that header has the
// derivation and the symbols.
//
// The material's fibre quantities live in one layer of marschnerTables
// (hairMaterials.glsl), texel (q, j) holding quantity q at cos theta node j:
//   q = 0 a_f (mean forward attenuation), 1 A_b, 2 Delta_b, 3 sigma_b^2,
//   4 beta_f^2, 5..7 N^G_R, N^G_TT, N^G_TRT (a_f,p / pi), 8..10 a_b,p / pi (RGB each);
// sampled at s = (q + 1/2) / width, t = cos theta: linear in cos theta.
// Needs marschner.glsl.

const int DUAL_SCATTERING_QUANTITIES = 11;
// T below this counts as this (DualScattering.cpp kMinTransmittance).
const float DUAL_SCATTERING_MIN_TRANSMITTANCE = 1e-6;
// theta_h variances clamped as marschnerLongitudinal clamps beta.
const float DUAL_SCATTERING_MIN_VARIANCE = (0.5 * MARSCHNER_PI / 180.0) * (0.5 * MARSCHNER_PI / 180.0);
const float DUAL_SCATTERING_MAX_VARIANCE = 9.0;

struct DualScatteringFibre {
    vec3 aF;       // mean forward attenuation
    vec3 Ab;       // A_b, eq. 11
    vec3 deltaB;   // Delta_b, eq. 16
    vec3 sigmaB2;  // sigma_b^2, eq. 17 squared
    vec3 betaF2;   // beta_f^2, eq. 14
    vec3 nG[3];      // N^G_p = a_f,p / pi, section 4.2
    vec3 nGBack[3];  // a_b,p / pi
};

DualScatteringFibre dualScatteringFibre(sampler2DArray tables, float layer, float cosTheta) {
    float width = float(textureSize(tables, 0).x);
    vec3 q[DUAL_SCATTERING_QUANTITIES];
    for (int i = 0; i < DUAL_SCATTERING_QUANTITIES; ++i)
        q[i] = texture(tables, vec3((float(i) + 0.5) / width, clamp(abs(cosTheta), 0.0, 1.0), layer)).rgb;
    DualScatteringFibre fibre;
    fibre.aF = q[0];
    fibre.Ab = q[1];
    fibre.deltaB = q[2];
    fibre.sigmaB2 = q[3];
    fibre.betaF2 = q[4];
    fibre.nG[0] = q[5];
    fibre.nG[1] = q[6];
    fibre.nG[2] = q[7];
    fibre.nGBack[0] = q[8];
    fibre.nGBack[1] = q[9];
    fibre.nGBack[2] = q[10];
    return fibre;
}

float dualScatteringMean(vec3 v) { return (v.x + v.y + v.z) / 3.0; }

// M_dEon(theta_i, theta_r - 2 shift) with theta_h variance sigma^2.
float dualScatteringLongitudinal(MarschnerAngles angles, float shift, float variance) {
    float clamped = clamp(variance, DUAL_SCATTERING_MIN_VARIANCE, DUAL_SCATTERING_MAX_VARIANCE);
    return marschnerLongitudinal(angles.sinThetaI, angles.cosThetaI, angles.sinThetaR, angles.cosThetaR, shift,
                                 sqrt(clamped));
}

// What multiple scattering adds towards wo per unit irradiance from wi
// (unshadowed), the light reaching the fibre with shadow transmittance T:
// Zinke's F() less its single scattering T f_s. densities: (d_f, d_b);
// lobeVariance: an SRBF lobe's 1/(4 lambda), else 0.
vec3 dualScattering(vec3 t, vec3 wi, vec3 wo, DualScatteringFibre fibre, vec3 alpha, vec3 beta, float transmittance,
                    vec2 densities, float lobeVariance) {
    MarschnerAngles angles = marschnerAngles(t, wi, wo);
    float T = clamp(transmittance, 0.0, 1.0);
    // The fibres in front along the light path: T_f = T^(1 - a_f), eq. 7's spread n beta_f^2.
    float n = -log(max(T, DUAL_SCATTERING_MIN_TRANSMITTANCE));
    vec3 Tf = exp(-n * (vec3(1.0) - fibre.aF));
    float spreadF = n * dualScatteringMean(fibre.betaF2);
    float shiftB = dualScatteringMean(fibre.deltaB), varianceB = dualScatteringMean(fibre.sigmaB2);
    // The azimuthal weights: x's lobes averaged over the half circle about
    // the eye's azimuth phi from the light (a share phi / pi of it forward);
    // what comes back spread as (pi - phi) / pi^2.
    float phi = clamp(angles.phi, 0.0, MARSCHNER_PI);
    float forwardShare = phi / MARSCHNER_PI;
    float backAzimuthal = (MARSCHNER_PI - phi) / (MARSCHNER_PI * MARSCHNER_PI);
    // Eqs. 9 and 15 (carrying A_b), and section 4.2's f_s^G.
    vec3 fBack = fibre.Ab * (dualScatteringLongitudinal(angles, shiftB, varianceB + lobeVariance) * backAzimuthal);
    vec3 fBackG = fibre.Ab * (dualScatteringLongitudinal(angles, shiftB, varianceB + spreadF + lobeVariance) *
                              backAzimuthal);
    vec3 fsG = vec3(0.0);
    for (int p = 0; p < 3; ++p) {
        float b = max(abs(beta[p]), 0.5 * MARSCHNER_PI / 180.0);
        vec3 nG = forwardShare * fibre.nG[p] + (1.0 - forwardShare) * fibre.nGBack[p];
        fsG += nG * dualScatteringLongitudinal(angles, alpha[p], b * b + spreadF + lobeVariance);
    }
    vec3 scattered = max(Tf - vec3(T), vec3(0.0));
    vec3 added = T * densities.y * fBack + densities.x * scattered * (fsG + densities.y * fBackG);
    return max(added, vec3(0.0));
}

// A uniform dome of radiance 1, unshadowed: d_b A_b.
vec3 dualScatteringUniformDome(DualScatteringFibre fibre, vec2 densities) {
    return max(densities.y * fibre.Ab, vec3(0.0));
}
