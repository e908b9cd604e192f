// Marschner's azimuthal terms N_p evaluated per fragment instead of read from
// tables: for hair whose absorption or index of refraction varies per curve
// or per vertex (no per-material table fits it), and as the reference the
// setting marschner:azimuthal = analytic selects. A formula-for-formula port of
// hdHair/shading/Marschner.cpp (azimuthalSetup, attenuation, azimuthalRoots,
// azimuthalTRT), in single precision; the equation numbers are Marschner et
// al. 2003's and hdHair/shading/Marschner.h explains every departure.
// Needs marschner.glsl.

// A fibre's parameters where they reach the fragment (MarschnerParameters).
struct MarschnerFibre {
    vec3 sigmaA;  // sigma_a per fibre radius, >= 0
    float eta;    // index of refraction, >= 1
    vec3 alpha;   // alpha_R, alpha_TT, alpha_TRT, radians
    vec3 beta;    // beta_R, beta_TT, beta_TRT, radians
    float glintScale, causticWidth, causticFade, causticLimit;  // k_G, w_c, delta eta', delta h_M
};

// |dphi/dgamma| below this counts as this (kMarschnerMinDPhiDGamma).
const float MARSCHNER_MIN_DPHI_DGAMMA = 1e-3;

// What N_p needs for one inclination (Marschner.cpp Azimuthal).
struct MarschnerAzimuthalSetup {
    float invEtaPrime;  // 1/eta' (Bravais, Appendix B)
    float etaPrime;
    float eta;
    float cosTheta;
    float c;       // asin(1/eta'), eq. (10)
    vec3 sigmaA;   // sigma_a' = sigma_a / cos theta_t
};

// Unpolarised Fresnel reflectance entering a dielectric of index eta >= 1 at
// incidence cosine cosXi (Marschner.cpp fresnel).
float marschnerFresnel(float eta, float cosXi) {
    float cosI = clamp(cosXi, 0.0, 1.0);
    float sinT2 = (1.0 - cosI * cosI) / (eta * eta);
    float cosT = sqrt(max(0.0, 1.0 - sinT2));
    float ds = cosI + eta * cosT, dp = eta * cosI + cosT;
    float rs = ds > 1e-30 ? (cosI - eta * cosT) / ds : 1.0;
    float rp = dp > 1e-30 ? (eta * cosI - cosT) / dp : 1.0;
    return clamp(0.5 * (rs * rs + rp * rp), 0.0, 1.0);
}

MarschnerAzimuthalSetup marschnerAzimuthalSetup(float cosTheta, MarschnerFibre fibre) {
    float eta = (isnan(fibre.eta) || isinf(fibre.eta)) ? 1.55 : max(1.0, fibre.eta);
    float cosThetaD = clamp((isnan(cosTheta) || isinf(cosTheta)) ? 1.0 : abs(cosTheta), 0.0, 1.0);
    float s = sqrt(max(0.0, 1.0 - cosThetaD * cosThetaD));
    MarschnerAzimuthalSetup a;
    a.eta = eta;
    a.cosTheta = cosThetaD;
    float root = sqrt(max(0.0, eta * eta - s * s));
    a.invEtaPrime = root > 0.0 ? clamp(cosThetaD / root, 0.0, 1.0) : 1.0;
    a.etaPrime = 1.0 / max(a.invEtaPrime, 1e-30);
    a.c = asin(a.invEtaPrime);
    float cosThetaT = max(sqrt(max(0.0, 1.0 - s * s / (eta * eta))), 1e-6);
    vec3 sigma = fibre.sigmaA;
    for (int i = 0; i < 3; ++i) sigma[i] = (isnan(sigma[i]) || isinf(sigma[i])) ? 0.0 : clamp(sigma[i], 0.0, 1e30);
    a.sigmaA = sigma / cosThetaT;
    return a;
}

// A(p, h), eqs. (5), (6), (9); T = exp(-sigma_a' * chord), chord = 2 cos gamma_t.
vec3 marschnerAttenuation(int p, float h, MarschnerAzimuthalSetup a) {
    float f = marschnerFresnel(a.eta, a.cosTheta * sqrt(max(0.0, 1.0 - h * h)));
    if (p == 0) return vec3(f);
    float cosGammaT = sqrt(max(0.0, 1.0 - h * h * a.invEtaPrime * a.invEtaPrime));
    float fresnelPart = (1.0 - f) * (1.0 - f) * (p == 1 ? 1.0 : f);  // F^(p-1), p = 1 or 2
    return fresnelPart * exp(-a.sigmaA * (2.0 * cosGammaT * float(p)));
}

// The cubic of eq. (10): phi(p, gamma) = b gamma + a gamma^3 + p pi.
vec2 marschnerCubic(int p, MarschnerAzimuthalSetup az) {
    float pf = float(p);
    return vec2(-8.0 * pf * az.c / (MARSCHNER_PI * MARSCHNER_PI * MARSCHNER_PI), 6.0 * pf * az.c / MARSCHNER_PI - 2.0);
}

float marschnerCubeRoot(float x) { return sign(x) * pow(abs(x), 1.0 / 3.0); }

// Real roots of a x^3 + b x + d = 0, polished by Newton steps; returns the count.
int marschnerSolveDepressedCubic(float a, float b, float d, out vec3 roots) {
    int count = 0;
    roots = vec3(0.0);
    if (abs(a) < 1e-12 * max(1.0, abs(b))) {
        if (abs(b) < 1e-30) return 0;
        roots[0] = -d / b;
        count = 1;
    } else {
        float P = b / a, Q = d / a;
        float discriminant = 0.25 * Q * Q + P * P * P / 27.0;
        if (discriminant > 0.0) {
            float s = sqrt(discriminant);
            roots[0] = marschnerCubeRoot(-0.5 * Q + s) + marschnerCubeRoot(-0.5 * Q - s);
            count = 1;
        } else if (P < 0.0) {
            float r = 2.0 * sqrt(-P / 3.0);
            float angle = acos(clamp(1.5 * Q / P * sqrt(-3.0 / P), -1.0, 1.0)) / 3.0;
            for (int k = 0; k < 3; ++k) roots[k] = r * cos(angle - 2.0 * MARSCHNER_PI * float(k) / 3.0);
            count = 3;
        } else {
            count = 1;  // P = Q = 0: the root 0
        }
    }
    for (int i = 0; i < count; ++i) {
        for (int iteration = 0; iteration < 3; ++iteration) {
            float x = roots[i];
            float value = a * x * x * x + b * x + d, slope = 3.0 * a * x * x + b;
            if (abs(slope) < 1e-12) break;
            float next = x - value / slope;
            if (isnan(next) || isinf(next)) break;
            roots[i] = next;
        }
    }
    return count;
}

// N_p(p, phi) of eq. (8) without the caustic treatment: every root summed.
vec3 marschnerAzimuthalRoots(int p, float phi, MarschnerAzimuthalSetup az) {
    const float halfPi = 0.5 * MARSCHNER_PI;
    if (p == 0) {
        // phi = -2 gamma_i, one root for phi in [-pi, pi].
        float gamma = -0.5 * phi;
        return marschnerAttenuation(0, sin(gamma), az) * (cos(gamma) / 4.0);
    }
    vec2 k = marschnerCubic(p, az);  // (a, b)
    float pPi = float(p) * MARSCHNER_PI;
    // |phi(p, gamma) - p pi| <= |b| pi/2 + |a| pi^3/8 on |gamma| <= pi/2: try every phi + 2 pi m there.
    float reach = abs(k.y) * halfPi + abs(k.x) * MARSCHNER_PI * MARSCHNER_PI * MARSCHNER_PI / 8.0;
    int mLow = int(floor((pPi - reach - phi) / (2.0 * MARSCHNER_PI)));
    int mHigh = int(ceil((pPi + reach - phi) / (2.0 * MARSCHNER_PI)));
    vec3 sum = vec3(0.0);
    for (int m = mLow; m <= mHigh; ++m) {
        float target = phi + 2.0 * MARSCHNER_PI * float(m);
        vec3 roots;
        int count = marschnerSolveDepressedCubic(k.x, k.y, pPi - target, roots);
        for (int i = 0; i < count; ++i) {
            float gamma = roots[i];
            if (isnan(gamma) || isinf(gamma) || abs(gamma) > halfPi + 1e-6) continue;
            gamma = clamp(gamma, -halfPi, halfPi);
            float derivative = max(abs(k.y + 3.0 * k.x * gamma * gamma), MARSCHNER_MIN_DPHI_DGAMMA);
            // |2 dphi/dh|^-1 = cos gamma_i / (2 |dphi/dgamma|)
            sum += marschnerAttenuation(p, sin(gamma), az) * (cos(gamma) / (2.0 * derivative));
        }
    }
    return sum;
}

float marschnerWrappedAngle(float x) {
    return x - 2.0 * MARSCHNER_PI * floor((x + MARSCHNER_PI) / (2.0 * MARSCHNER_PI));
}

// N_TRT with Marschner section 4.3's caustic replacement (Marschner.cpp azimuthalTRT).
vec3 marschnerAzimuthalTRT(float phi, MarschnerAzimuthalSetup az, MarschnerFibre fibre) {
    vec2 k = marschnerCubic(2, az);
    float causticLimit = max(0.0, fibre.causticLimit);
    float width = max(1e-3, fibre.causticWidth);
    float fade = max(1e-6, fibre.causticFade);
    float hc = 0.0, phiC = 0.0, deltaH = causticLimit, t = 1.0;
    if (az.etaPrime < 2.0 && k.y > 0.0 && k.x < 0.0) {
        // dphi/dgamma = b + 3 a gamma^2 = 0
        float gammaC = min(sqrt(-k.y / (3.0 * k.x)), 0.5 * MARSCHNER_PI);
        hc = sin(gammaC);
        phiC = marschnerWrappedAngle(k.y * gammaC + k.x * gammaC * gammaC * gammaC + 2.0 * MARSCHNER_PI);
        // d2phi/dh2 at the caustic = phi''(gamma_c) / cos^2 gamma_c, phi'' = 6 a gamma.
        float cosC = max(cos(gammaC), 1e-6);
        float second = abs(6.0 * k.x * gammaC) / (cosC * cosC);
        deltaH = second > 0.0 ? min(causticLimit, 2.0 * sqrt(2.0 * width / second)) : causticLimit;
    } else {
        t = 1.0 - smoothstep(0.0, 1.0, (az.etaPrime - 2.0) / fade);  // fade 1 -> 0 over [2, 2 + delta eta']
    }
    float left = marschnerWrappedAngle(phi - phiC), right = marschnerWrappedAngle(phi + phiC);
    left = exp(-0.5 * left * left / (width * width));  // g(w; x) / g(w; 0)
    right = exp(-0.5 * right * right / (width * width));
    float g0 = 1.0 / (width * sqrt(2.0 * MARSCHNER_PI));
    vec3 n = marschnerAzimuthalRoots(2, phi, az) * ((1.0 - t * left) * (1.0 - t * right));
    vec3 glint = marschnerAttenuation(2, hc, az) * (t * max(0.0, fibre.glintScale) * deltaH * g0 * (left + right));
    return n + glint;
}

vec3 marschnerFiniteOrZero(vec3 v) {
    for (int i = 0; i < 3; ++i) v[i] = (isnan(v[i]) || isinf(v[i])) ? 0.0 : max(v[i], 0.0);
    return v;
}

MarschnerLobes marschnerAnalyticLobes(vec3 t, vec3 wi, vec3 wo, MarschnerFibre fibre) {
    MarschnerAngles angles = marschnerAngles(t, wi, wo);
    // N_p at theta_r for every lobe (Marschner.h, "Which inclination").
    MarschnerAzimuthalSetup az = marschnerAzimuthalSetup(angles.cosThetaR, fibre);
    vec3 nR = marschnerFiniteOrZero(marschnerAzimuthalRoots(0, angles.phi, az));
    vec3 nTT = marschnerFiniteOrZero(marschnerAzimuthalRoots(1, angles.phi, az));
    vec3 nTRT = marschnerFiniteOrZero(marschnerAzimuthalTRT(angles.phi, az, fibre));
    return marschnerCombineLobes(angles, nR, nTT, nTRT, fibre.alpha, fibre.beta);
}

// R + TT + TRT: the radiance towards wo per unit irradiance from wi.
vec3 marschnerAnalytic(vec3 t, vec3 wi, vec3 wo, MarschnerFibre fibre) {
    MarschnerLobes lobes = marschnerAnalyticLobes(t, wi, wo, fibre);
    return lobes.R + lobes.TT + lobes.TRT;
}
