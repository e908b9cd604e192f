#include "hdHair/shading/Marschner.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace hdhair {
namespace {

constexpr double kPi = 3.14159265358979323846;

glm::vec3 normalizedOrZero(const glm::vec3& v) {
    float length = glm::length(v);
    return (std::isfinite(length) && length > 1e-20f) ? v / length : glm::vec3(0.0f);
}

double safeSqrt(double x) { return std::sqrt(std::max(0.0, x)); }

double finiteOrZero(double x) { return std::isfinite(x) ? std::max(0.0, x) : 0.0; }

// log I0(x), x >= 0: power series below 12 (summed to convergence), the
// asymptotic expansion e^x/√(2πx)·(1 + 1/(8x) + 9/(128x²)) above.
double logBesselI0(double x) {
    if (x > 12.0) {
        double inverse = 1.0 / x;
        return x - 0.5 * std::log(2.0 * kPi * x) + std::log1p(inverse * (0.125 + inverse * 9.0 / 128.0));
    }
    double quarterSquare = 0.25 * x * x, term = 1.0, sum = 1.0;
    for (int k = 1; k < 64 && term > 1e-17 * sum; ++k) {
        term *= quarterSquare / (double(k) * double(k));
        sum += term;
    }
    return std::log(sum);
}

// Unpolarised Fresnel reflectance of a dielectric of index η >= 1 entered
// from air at incidence cosine cosXi (the true 3D angle at the fibre surface,
// cos ξ = cos θ cos γ_i). No total internal reflection from outside.
double fresnel(double eta, double cosXi) {
    double cosI = std::clamp(cosXi, 0.0, 1.0);
    double sinT2 = (1.0 - cosI * cosI) / (eta * eta);
    double cosT = safeSqrt(1.0 - sinT2);
    double ds = cosI + eta * cosT, dp = eta * cosI + cosT;
    double rs = ds > 1e-300 ? (cosI - eta * cosT) / ds : 1.0;
    double rp = dp > 1e-300 ? (eta * cosI - cosT) / dp : 1.0;
    return std::clamp(0.5 * (rs * rs + rp * rp), 0.0, 1.0);
}

// What N_p needs for one θ_d.
struct Azimuthal {
    double invEtaPrime = 1.0;  // 1/η'
    double etaPrime = 1.0;     // η' (huge but finite at grazing)
    double etaSecond = 1.0;    // η'' (documentation only: see fresnel())
    double eta = 1.55;         // η
    double cosTheta = 1.0;     // cos θ of the inclination the table is indexed by
    double c = kPi / 2.0;      // asin(1/η')
    glm::dvec3 sigmaA{0.0};    // σ_a' = σ_a / cos θ_t
};

Azimuthal azimuthalSetup(double cosTheta, const MarschnerParameters& parameters) {
    double eta = std::isfinite(parameters.eta) ? std::max(1.0, double(parameters.eta)) : 1.55;
    double cosThetaD = std::clamp(std::isfinite(cosTheta) ? std::abs(cosTheta) : 1.0, 0.0, 1.0);
    double s = safeSqrt(1.0 - cosThetaD * cosThetaD);
    Azimuthal a;
    a.eta = eta;
    a.cosTheta = cosThetaD;
    double root = safeSqrt(eta * eta - s * s);  // >= √(η² − 1) >= 0
    a.invEtaPrime = root > 0.0 ? std::clamp(cosThetaD / root, 0.0, 1.0) : 1.0;
    a.etaPrime = 1.0 / std::max(a.invEtaPrime, 1e-300);
    a.etaSecond = eta * eta * a.invEtaPrime;
    a.c = std::asin(a.invEtaPrime);
    double cosThetaT = std::max(safeSqrt(1.0 - s * s / (eta * eta)), 1e-6);
    for (int i = 0; i < 3; ++i) {
        double sigma = std::isfinite(parameters.sigmaA[i]) ? std::max(0.0, double(parameters.sigmaA[i])) : 0.0;
        a.sigmaA[i] = std::min(sigma, 1e30) / cosThetaT;
    }
    return a;
}

// A(p, h), eqs. (5), (6), (9) with the entry Fresnel factor for the exits.
glm::dvec3 attenuation(int p, double h, const Azimuthal& a) {
    double f = fresnel(a.eta, a.cosTheta * safeSqrt(1.0 - h * h));
    if (p == 0) return glm::dvec3(f);
    double cosGammaT = safeSqrt(1.0 - h * h * a.invEtaPrime * a.invEtaPrime);
    double chord = 2.0 * cosGammaT;  // in fibre radii
    double fresnelPart = (1.0 - f) * (1.0 - f) * std::pow(f, p - 1);
    glm::dvec3 result;
    for (int i = 0; i < 3; ++i) result[i] = fresnelPart * std::exp(-a.sigmaA[i] * chord * double(p));
    return result;
}

// The cubic of eq. (10): φ(p, γ) ≈ bγ + aγ³ + pπ.
struct Cubic {
    double a, b;
};
Cubic cubicFor(int p, const Azimuthal& az) {
    return {-8.0 * p * az.c / (kPi * kPi * kPi), 6.0 * p * az.c / kPi - 2.0};
}
double cubicPhi(int p, const Cubic& k, double gamma) { return k.b * gamma + k.a * gamma * gamma * gamma + p * kPi; }
double cubicDPhiDGamma(const Cubic& k, double gamma) { return k.b + 3.0 * k.a * gamma * gamma; }

// Real roots of a x³ + b x + d = 0, polished by Newton steps; returns count.
int solveDepressedCubic(double a, double b, double d, double roots[3]) {
    int count = 0;
    if (std::abs(a) < 1e-12 * std::max(1.0, std::abs(b))) {
        if (std::abs(b) < 1e-300) return 0;
        roots[count++] = -d / b;
    } else {
        double P = b / a, Q = d / a;
        double discriminant = 0.25 * Q * Q + P * P * P / 27.0;
        if (discriminant > 0.0) {
            double s = std::sqrt(discriminant);
            roots[count++] = std::cbrt(-0.5 * Q + s) + std::cbrt(-0.5 * Q - s);
        } else if (P < 0.0) {
            double r = 2.0 * std::sqrt(-P / 3.0);
            double angle = std::acos(std::clamp(1.5 * Q / P * std::sqrt(-3.0 / P), -1.0, 1.0)) / 3.0;
            for (int k = 0; k < 3; ++k) roots[count++] = r * std::cos(angle - 2.0 * kPi * k / 3.0);
        } else {
            roots[count++] = 0.0;  // P = Q = 0
        }
    }
    for (int i = 0; i < count; ++i) {
        for (int iteration = 0; iteration < 3; ++iteration) {
            double x = roots[i];
            double value = a * x * x * x + b * x + d, slope = 3.0 * a * x * x + b;
            if (std::abs(slope) < 1e-12) break;
            double next = x - value / slope;
            if (!std::isfinite(next)) break;
            roots[i] = next;
        }
    }
    return count;
}

// N_p(p, φ) of eq. (8) without the caustic treatment: the sum over every root.
glm::dvec3 azimuthalRoots(int p, double phi, const Azimuthal& az) {
    glm::dvec3 sum(0.0);
    constexpr double halfPi = kPi / 2.0;
    if (p == 0) {
        // φ = −2γ_i, one root for φ ∈ [−π, π].
        double gamma = -0.5 * phi;
        double h = std::sin(gamma);
        return attenuation(0, h, az) * (std::cos(gamma) / (2.0 * 2.0));
    }
    Cubic k = cubicFor(p, az);
    // |φ(p, γ) − pπ| <= |b|π/2 + |a|π³/8 on |γ| <= π/2: try every φ + 2πm there.
    double reach = std::abs(k.b) * halfPi + std::abs(k.a) * kPi * kPi * kPi / 8.0;
    int mLow = int(std::floor((p * kPi - reach - phi) / (2.0 * kPi)));
    int mHigh = int(std::ceil((p * kPi + reach - phi) / (2.0 * kPi)));
    for (int m = mLow; m <= mHigh; ++m) {
        double target = phi + 2.0 * kPi * m;
        double roots[3];
        int count = solveDepressedCubic(k.a, k.b, p * kPi - target, roots);
        for (int i = 0; i < count; ++i) {
            double gamma = roots[i];
            if (!std::isfinite(gamma) || std::abs(gamma) > halfPi + 1e-9) continue;
            gamma = std::clamp(gamma, -halfPi, halfPi);
            double derivative = std::max(std::abs(cubicDPhiDGamma(k, gamma)), kMarschnerMinDPhiDGamma);
            // |2 dφ/dh|⁻¹ = cos γ_i / (2 |dφ/dγ|)
            sum += attenuation(p, std::sin(gamma), az) * (std::cos(gamma) / (2.0 * derivative));
        }
    }
    return sum;
}

double wrappedAngle(double x) {
    x = std::fmod(x + kPi, 2.0 * kPi);
    if (x < 0.0) x += 2.0 * kPi;
    return x - kPi;
}

// N_TRT with Marschner §4.3's caustic replacement.
glm::dvec3 azimuthalTRT(double phi, const Azimuthal& az, const MarschnerParameters& parameters) {
    const int p = 2;
    Cubic k = cubicFor(p, az);
    double causticLimit = std::max(0.0, double(parameters.causticLimit));
    double width = std::max(1e-3, double(parameters.causticWidth));
    double fade = std::max(1e-6, double(parameters.causticFade));
    double hc = 0.0, phiC = 0.0, deltaH = causticLimit, t = 1.0;
    if (az.etaPrime < 2.0 && k.b > 0.0 && k.a < 0.0) {
        // dφ/dγ = b + 3aγ² = 0
        double gammaC = std::min(std::sqrt(-k.b / (3.0 * k.a)), kPi / 2.0);
        hc = std::sin(gammaC);
        phiC = wrappedAngle(cubicPhi(p, k, gammaC));
        // ∂²φ/∂h² at the caustic = φ''(γ_c)/cos²γ_c, φ'' = 6aγ.
        double cosC = std::max(std::cos(gammaC), 1e-6);
        double second = std::abs(6.0 * k.a * gammaC) / (cosC * cosC);
        deltaH = second > 0.0 ? std::min(causticLimit, 2.0 * std::sqrt(2.0 * width / second)) : causticLimit;
    } else {
        double x = std::clamp((az.etaPrime - 2.0) / fade, 0.0, 1.0);
        t = 1.0 - x * x * (3.0 - 2.0 * x);  // smoothstep fade 1 → 0 over [2, 2 + Δη']
    }
    auto gaussianRatio = [&](double x) { return std::exp(-0.5 * x * x / (width * width)); };  // g(w;x)/g(w;0)
    double g0 = 1.0 / (width * std::sqrt(2.0 * kPi));
    double left = gaussianRatio(wrappedAngle(phi - phiC)), right = gaussianRatio(wrappedAngle(phi + phiC));
    glm::dvec3 n = azimuthalRoots(p, phi, az) * ((1.0 - t * left) * (1.0 - t * right));
    glm::dvec3 glint = attenuation(p, hc, az) *
                       (t * std::max(0.0, double(parameters.glintScale)) * deltaH * g0 * (left + right));
    return n + glint;
}

glm::vec3 toFiniteVec3(const glm::dvec3& v) {
    return glm::vec3(float(finiteOrZero(v.x)), float(finiteOrZero(v.y)), float(finiteOrZero(v.z)));
}

}  // namespace

MarschnerParameters marschnerParametersFromR(float alphaR, float betaR) {
    MarschnerParameters parameters;
    parameters.alpha = glm::vec3(alphaR, -0.5f * alphaR, -1.5f * alphaR);
    parameters.beta = glm::vec3(betaR, 0.5f * betaR, 2.0f * betaR);
    return parameters;
}

float marschnerLongitudinalVariance(float beta) {
    float b = std::isfinite(beta) ? std::max(std::abs(beta), 0.5f * kMarschnerDegrees) : 0.5f * kMarschnerDegrees;
    b = std::min(b, 3.0f);
    return 4.0f * b * b;
}

namespace {
double chiangDenominator(double betaN) {
    double b = std::clamp(std::isfinite(betaN) ? betaN : 0.3, 0.0, 1.0);
    return 5.969 - 0.215 * b + 2.532 * b * b - 10.73 * b * b * b + 5.574 * b * b * b * b +
           0.245 * b * b * b * b * b;
}
}  // namespace

glm::vec3 marschnerSigmaAFromColor(const glm::vec3& color, float azimuthalRoughness) {
    double denominator = chiangDenominator(azimuthalRoughness);
    glm::vec3 sigma;
    for (int i = 0; i < 3; ++i) {
        double c = std::clamp(std::isfinite(color[i]) ? double(color[i]) : 1.0, 1e-4, 1.0);
        double x = std::log(c) / denominator;
        sigma[i] = float(x * x);
    }
    return sigma;
}

glm::vec3 marschnerColorFromSigmaA(const glm::vec3& sigmaA, float azimuthalRoughness) {
    double denominator = chiangDenominator(azimuthalRoughness);
    glm::vec3 color;
    for (int i = 0; i < 3; ++i) {
        double s = std::isfinite(sigmaA[i]) ? std::max(0.0, double(sigmaA[i])) : 0.0;
        color[i] = float(std::exp(-std::sqrt(s) * denominator));
    }
    return color;
}

glm::vec3 marschnerSigmaAFromConcentration(float eumelanin, float pheomelanin) {
    auto clean = [](float x) { return std::isfinite(x) ? std::max(0.0f, x) : 0.0f; };
    return clean(eumelanin) * glm::vec3(0.419f, 0.697f, 1.37f) + clean(pheomelanin) * glm::vec3(0.187f, 0.4f, 1.05f);
}

glm::vec3 marschnerSigmaAFromMelanin(float melanin, float redness) {
    float m = std::clamp(std::isfinite(melanin) ? melanin : 0.0f, 0.0f, 0.9999f);
    float r = std::clamp(std::isfinite(redness) ? redness : 0.0f, 0.0f, 1.0f);
    float concentration = -std::log1p(-m);
    return marschnerSigmaAFromConcentration(concentration * (1.0f - r), concentration * r);
}

MarschnerAngles marschnerAngles(const glm::vec3& t, const glm::vec3& wi, const glm::vec3& wo) {
    glm::vec3 tn = normalizedOrZero(t), in = normalizedOrZero(wi), on = normalizedOrZero(wo);
    MarschnerAngles angles;
    angles.sinThetaI = std::clamp(glm::dot(tn, in), -1.0f, 1.0f);
    angles.sinThetaR = std::clamp(glm::dot(tn, on), -1.0f, 1.0f);
    angles.cosThetaI = std::sqrt(std::max(0.0f, 1.0f - angles.sinThetaI * angles.sinThetaI));
    angles.cosThetaR = std::sqrt(std::max(0.0f, 1.0f - angles.sinThetaR * angles.sinThetaR));
    // Azimuth: the angle between the projections onto the normal plane.
    glm::vec3 pi = in - angles.sinThetaI * tn, po = on - angles.sinThetaR * tn;
    float lengths = glm::length(pi) * glm::length(po);
    if (std::isfinite(lengths) && lengths > 1e-12f)
        angles.phi = std::atan2(glm::length(glm::cross(pi, po)), glm::dot(pi, po));
    // cos(θ_r − θ_i) = cos θ_r cos θ_i + sin θ_r sin θ_i; sin²|θ_d| = (1 − cos(θ_r − θ_i))/2
    double cosDifference = double(angles.cosThetaR) * angles.cosThetaI + double(angles.sinThetaR) * angles.sinThetaI;
    double sinD = std::sqrt(std::clamp(0.5 * (1.0 - cosDifference), 0.0, 1.0));
    angles.sinThetaD = float(angles.sinThetaR >= angles.sinThetaI ? sinD : -sinD);  // sign of θ_r − θ_i
    angles.cosThetaD = float(std::sqrt(std::clamp(0.5 * (1.0 + cosDifference), 0.0, 1.0)));
    return angles;
}

float marschnerLongitudinal(float sinThetaI, float cosThetaI, float sinThetaR, float cosThetaR, float alpha,
                            float variance) {
    double v = std::isfinite(variance) ? std::max(double(variance), 1e-6) : 1e-6;
    double a2 = std::isfinite(alpha) ? 2.0 * double(alpha) : 0.0;
    // θ_r' = θ_r − 2α; |cos θ_r'| keeps θ_r' on the sphere (pbrt-v4).
    double sinR = double(sinThetaR) * std::cos(a2) - double(cosThetaR) * std::sin(a2);
    double cosR = std::abs(double(cosThetaR) * std::cos(a2) + double(sinThetaR) * std::sin(a2));
    double a = double(cosThetaI) * cosR / v, b = double(sinThetaI) * sinR / v;
    double m;
    if (v <= 0.1) {
        // csch(1/v)/(2v) = e^(−1/v)/(v (1 − e^(−2/v))); the last factor is 1 to double precision.
        m = std::exp(logBesselI0(a) - b - 1.0 / v - std::log(v));
    } else {
        m = std::exp(-b) * std::exp(logBesselI0(a)) / (2.0 * v * std::sinh(1.0 / v));
    }
    return float(finiteOrZero(m));
}

glm::vec3 marschnerAzimuthal(int p, float phi, float cosTheta, const MarschnerParameters& parameters) {
    double angle = std::isfinite(phi) ? std::abs(wrappedAngle(double(phi))) : 0.0;
    Azimuthal az = azimuthalSetup(cosTheta, parameters);
    if (p == 2) return toFiniteVec3(azimuthalTRT(angle, az, parameters));
    if (p == 0 || p == 1) return toFiniteVec3(azimuthalRoots(p, angle, az));
    return glm::vec3(0.0f);
}

glm::vec3 marschnerAttenuation(int p, float h, float cosTheta, const MarschnerParameters& parameters) {
    if (p < 0 || p > 2) return glm::vec3(0.0f);
    double offset = std::isfinite(h) ? std::clamp(double(h), -1.0, 1.0) : 0.0;
    return toFiniteVec3(attenuation(p, offset, azimuthalSetup(cosTheta, parameters)));
}

MarschnerLobes combineMarschnerLobes(const MarschnerAngles& angles, const glm::vec3& nR, const glm::vec3& nTT,
                                     const glm::vec3& nTRT, const MarschnerParameters& parameters) {
    MarschnerLobes lobes;
    const glm::vec3* n[3] = {&nR, &nTT, &nTRT};
    glm::vec3* out[3] = {&lobes.R, &lobes.TT, &lobes.TRT};
    for (int p = 0; p < 3; ++p) {
        float m = marschnerLongitudinal(angles.sinThetaI, angles.cosThetaI, angles.sinThetaR, angles.cosThetaR,
                                        parameters.alpha[p], marschnerLongitudinalVariance(parameters.beta[p]));
        for (int i = 0; i < 3; ++i) {
            float value = m * (*n[p])[i];
            (*out[p])[i] = std::isfinite(value) ? std::max(0.0f, value) : 0.0f;
        }
    }
    lobes.S = lobes.radiance() / std::max(angles.cosThetaI, 1e-4f);
    return lobes;
}

MarschnerLobes evaluateMarschner(const glm::vec3& t, const glm::vec3& wi, const glm::vec3& wo,
                                 const MarschnerParameters& parameters) {
    MarschnerAngles angles = marschnerAngles(t, wi, wo);
    // N_p is evaluated at θ_r for every lobe (header, "Which inclination").
    float c = angles.cosThetaR;
    return combineMarschnerLobes(angles, marschnerAzimuthal(0, angles.phi, c, parameters),
                                 marschnerAzimuthal(1, angles.phi, c, parameters),
                                 marschnerAzimuthal(2, angles.phi, c, parameters), parameters);
}

}  // namespace hdhair
