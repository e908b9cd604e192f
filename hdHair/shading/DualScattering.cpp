#include "hdHair/shading/DualScattering.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/packing.hpp>

namespace hdhair {
namespace {

constexpr float kPiF = 3.14159265358979323846f;
// The fibre count along a light path is −ln T; T below this counts as this
// (13.8 fibres), so that n stays finite where the maps are opaque.
constexpr float kMinTransmittance = 1e-6f;
// Variances (of θ_h) outside what M_dEon evaluates well are clamped as
// marschner.glsl clamps β: 0.5° .. 3 radians.
constexpr float kMinVariance = (0.5f * kMarschnerDegrees) * (0.5f * kMarschnerDegrees);
constexpr float kMaxVariance = 9.0f;

float finiteOr(float x, float fallback) { return std::isfinite(x) ? x : fallback; }
glm::vec3 finiteNonNegative(const glm::vec3& v) {
    return glm::vec3(std::max(0.0f, finiteOr(v.x, 0.0f)), std::max(0.0f, finiteOr(v.y, 0.0f)),
                     std::max(0.0f, finiteOr(v.z, 0.0f)));
}
float roundToHalf(float x) { return glm::unpackHalf1x16(glm::packHalf1x16(x)); }
float meanOf(const glm::vec3& v) { return (v.x + v.y + v.z) / 3.0f; }

// M_dEon(θ_i, θ_r − 2·shift) with θ_h variance σ² (v = 4σ², Marschner.h).
float longitudinal(const MarschnerAngles& angles, float shift, float variance) {
    float clamped = std::clamp(finiteOr(variance, kMaxVariance), kMinVariance, kMaxVariance);
    return marschnerLongitudinal(angles.sinThetaI, angles.cosThetaI, angles.sinThetaR, angles.cosThetaR, shift,
                                 4.0f * clamped);
}

// The quantities the table holds, in its order.
void fibreQuantities(const DualScatteringFibre& fibre, glm::vec3 out[kDualScatteringQuantities]) {
    out[0] = fibre.aF;
    out[1] = fibre.Ab;
    out[2] = fibre.deltaB;
    out[3] = fibre.sigmaB2;
    out[4] = fibre.betaF2;
    out[5] = fibre.nG[0];
    out[6] = fibre.nG[1];
    out[7] = fibre.nG[2];
    out[8] = fibre.nGBack[0];
    out[9] = fibre.nGBack[1];
    out[10] = fibre.nGBack[2];
}

// a_f,p and a_b,p at one inclination: the midpoint rule over each half of
// the circle; N_p is even in φ, so each half is twice its part of [0, π].
DualScatteringLobes dualScatteringLobesAt(const MarschnerParameters& parameters, float cosTheta, int azimuths) {
    const int steps = std::max(1, azimuths);
    const float dPhi = 0.5f * kPiF / float(steps);
    DualScatteringLobes lobes;
    for (int p = 0; p < 3; ++p) {
        glm::vec3 backward(0.0f), forward(0.0f);
        for (int k = 0; k < steps; ++k) {
            float phi = (float(k) + 0.5f) * dPhi;
            backward += marschnerAzimuthal(p, phi, cosTheta, parameters);
            forward += marschnerAzimuthal(p, 0.5f * kPiF + phi, cosTheta, parameters);
        }
        lobes.backward[p] = 2.0f * dPhi * backward;
        lobes.forward[p] = 2.0f * dPhi * forward;
    }
    return lobes;
}

}  // namespace

DualScatteringAttenuations buildDualScatteringAttenuations(const MarschnerParameters& parameters, int nodes,
                                                           int azimuths) {
    DualScatteringAttenuations result;
    result.nodes = std::max(1, nodes);
    result.forward.resize(std::size_t(result.nodes) * 3);
    result.backward.resize(std::size_t(result.nodes) * 3);
    for (int j = 0; j < result.nodes; ++j) {
        DualScatteringLobes lobes = dualScatteringLobesAt(parameters, (float(j) + 0.5f) / float(result.nodes), azimuths);
        for (int p = 0; p < 3; ++p) {
            result.forward[std::size_t(j) * 3 + p] = lobes.forward[p];
            result.backward[std::size_t(j) * 3 + p] = lobes.backward[p];
        }
    }
    return result;
}

DualScatteringFibre dualScatteringFibre(const DualScatteringLobes& lobes, const glm::vec3& alpha,
                                        const glm::vec3& beta, float backwardDensity) {
    DualScatteringFibre fibre;
    const float db = std::clamp(finiteOr(backwardDensity, 0.0f), 0.0f, 1.0f);
    glm::vec3 sumAlphaF(0.0f), sumAlphaB(0.0f), sumBetaF2(0.0f), sumBetaB2(0.0f);
    for (int p = 0; p < 3; ++p) {
        glm::vec3 f = finiteNonNegative(lobes.forward[p]), b = finiteNonNegative(lobes.backward[p]);
        float b2 = std::max(beta[p] * beta[p], kMinVariance);
        fibre.aF += f;
        fibre.aB += b;
        sumAlphaF += f * alpha[p];
        sumAlphaB += b * alpha[p];
        sumBetaF2 += f * b2;
        sumBetaB2 += b * b2;
        fibre.nG[p] = f / kPiF;      // (2/π)∫_{π/2}^{π} N_p dφ = a_f,p/π (§4.2)
        fibre.nGBack[p] = b / kPiF;  // the backward half's mean, a_b,p/π
    }
    for (int c = 0; c < 3; ++c) {
        // Eqs. 13, 14: the lobes' shifts and variances weighted by their
        // energy; a side with no energy takes the unweighted mean.
        float af = fibre.aF[c], ab = fibre.aB[c];
        fibre.alphaF[c] = af > 1e-8f ? sumAlphaF[c] / af : meanOf(alpha);
        fibre.alphaB[c] = ab > 1e-8f ? sumAlphaB[c] / ab : meanOf(alpha);
        float meanBeta2 = std::max(meanOf(beta * beta), kMinVariance);
        fibre.betaF2[c] = af > 1e-8f ? sumBetaF2[c] / af : meanBeta2;
        fibre.betaB2[c] = ab > 1e-8f ? sumBetaB2[c] / ab : meanBeta2;

        af = std::min(af, kDualScatteringMaxAttenuation);
        ab = std::min(ab, kDualScatteringMaxAttenuation);
        fibre.aF[c] = af;
        fibre.aB[c] = ab;
        const float oneMinusAf2 = 1.0f - af * af;
        const float ab3 = ab * ab * ab;
        // Eq. 11 with eqs. 13, 14: one (A_1) and three (A_3) backward events.
        const float a1 = ab * af * af / oneMinusAf2;
        const float a3 = ab3 * af * af / (oneMinusAf2 * oneMinusAf2 * oneMinusAf2);
        fibre.Ab[c] = a1 + a3;
        // Eq. 16: the average longitudinal shift of the back-scattered light.
        fibre.deltaB[c] = fibre.alphaB[c] * (1.0f - 2.0f * ab * ab / (oneMinusAf2 * oneMinusAf2)) +
                          fibre.alphaF[c] * (2.0f * oneMinusAf2 * oneMinusAf2 + 4.0f * af * af * ab * ab) /
                              (oneMinusAf2 * oneMinusAf2 * oneMinusAf2);
        // Eq. 17 as printed: its standard deviation.
        const float betaF = std::sqrt(fibre.betaF2[c]), betaB = std::sqrt(fibre.betaB2[c]);
        const float numerator = ab * std::sqrt(2.0f * fibre.betaF2[c] + fibre.betaB2[c]) +
                                ab3 * std::sqrt(2.0f * fibre.betaF2[c] + 3.0f * fibre.betaB2[c]);
        const float denominator = ab + ab3 * (2.0f * betaF + 3.0f * betaB);
        const float sigmaB = denominator > 1e-8f ? (1.0f + db * af * af) * numerator / denominator
                                                 : std::sqrt(fibre.betaB2[c]);
        fibre.sigmaB2[c] = std::clamp(sigmaB * sigmaB, kMinVariance, kMaxVariance);
    }
    fibre.Ab = finiteNonNegative(fibre.Ab);
    return fibre;
}

std::vector<std::uint16_t> DualScatteringTable::halfLayer(int width, int height) const {
    std::vector<std::uint16_t> layer(std::size_t(std::max(width, 0)) * std::max(height, 0) * 4,
                                     glm::packHalf1x16(0.0f));
    for (int j = 0; j < std::min(nodes, height); ++j)
        for (int q = 0; q < std::min(kDualScatteringQuantities, width); ++q) {
            const glm::vec3& value = values[std::size_t(j) * kDualScatteringQuantities + q];
            std::size_t texel = (std::size_t(j) * width + q) * 4;
            for (int c = 0; c < 3; ++c) layer[texel + c] = glm::packHalf1x16(value[c]);
        }
    return layer;
}

DualScatteringTable buildDualScatteringTable(const MarschnerParameters& parameters, float backwardDensity,
                                             int nodes) {
    DualScatteringAttenuations attenuations = buildDualScatteringAttenuations(parameters, nodes);
    DualScatteringTable table;
    table.nodes = attenuations.nodes;
    table.values.resize(std::size_t(table.nodes) * kDualScatteringQuantities);
    for (int j = 0; j < table.nodes; ++j) {
        DualScatteringLobes lobes;
        for (int p = 0; p < 3; ++p) {
            lobes.forward[p] = attenuations.forward[std::size_t(j) * 3 + p];
            lobes.backward[p] = attenuations.backward[std::size_t(j) * 3 + p];
        }
        glm::vec3 quantities[kDualScatteringQuantities];
        fibreQuantities(dualScatteringFibre(lobes, parameters.alpha, parameters.beta, backwardDensity), quantities);
        for (int q = 0; q < kDualScatteringQuantities; ++q)
            table.values[std::size_t(j) * kDualScatteringQuantities + q] =
                glm::vec3(roundToHalf(quantities[q].x), roundToHalf(quantities[q].y), roundToHalf(quantities[q].z));
    }
    return table;
}

DualScatteringFibre sampleDualScatteringTable(const DualScatteringTable& table, float cosTheta) {
    DualScatteringFibre fibre;
    if (table.nodes <= 0 || table.values.empty()) return fibre;
    // GL_LINEAR along t at texel centres, GL_CLAMP_TO_EDGE.
    float u = std::clamp(finiteOr(std::abs(cosTheta), 0.0f), 0.0f, 1.0f) * float(table.nodes) - 0.5f;
    float base = std::floor(u), weight = u - base;
    int j0 = std::clamp(int(base), 0, table.nodes - 1), j1 = std::clamp(int(base) + 1, 0, table.nodes - 1);
    glm::vec3 q[kDualScatteringQuantities];
    for (int i = 0; i < kDualScatteringQuantities; ++i)
        q[i] = table.values[std::size_t(j0) * kDualScatteringQuantities + i] * (1.0f - weight) +
               table.values[std::size_t(j1) * kDualScatteringQuantities + i] * weight;
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

glm::vec3 evaluateDualScattering(const glm::vec3& t, const glm::vec3& wi, const glm::vec3& wo,
                                 const MarschnerParameters& parameters, const DualScatteringFibre& fibre,
                                 float transmittance, const DualScatteringDensities& densities,
                                 float lobeVariance) {
    const MarschnerAngles angles = marschnerAngles(t, wi, wo);
    const float df = std::clamp(finiteOr(densities.forward, 0.0f), 0.0f, 1.0f);
    const float db = std::clamp(finiteOr(densities.backward, 0.0f), 0.0f, 1.0f);
    const float T = std::clamp(finiteOr(transmittance, 1.0f), 0.0f, 1.0f);
    const float lobe = std::max(finiteOr(lobeVariance, 0.0f), 0.0f);
    // The fibres in front of x along the light path, and what they pass on
    // (header: T_f = T^(1 − ā_f), σ̄_f² = n β_f², eq. 7).
    const float n = -std::log(std::max(T, kMinTransmittance));
    const glm::vec3 Tf(std::exp(-n * (1.0f - fibre.aF.x)), std::exp(-n * (1.0f - fibre.aF.y)),
                       std::exp(-n * (1.0f - fibre.aF.z)));
    // One shift and one width for the three channels (their mean): five
    // evaluations of M a light instead of fifteen.
    const float spreadF = n * meanOf(fibre.betaF2);
    const float shiftB = meanOf(fibre.deltaB), varianceB = meanOf(fibre.sigmaB2);
    const float mBack = longitudinal(angles, shiftB, varianceB + lobe);
    const float mBackG = longitudinal(angles, shiftB, varianceB + spreadF + lobe);
    // The azimuthal weights (header): the light scattered forward to x
    // arrives over the half circle about the light; seen at azimuth φ from
    // it, x's lobes are averaged over the half circle about φ, a fraction
    // φ/π of it forward. What comes back is spread as (π − φ)/π².
    const float phi = std::clamp(angles.phi, 0.0f, kPiF);
    const float forwardShare = phi / kPiF;
    const float backAzimuthal = (kPiF - phi) / (kPiF * kPiF);
    // Eqs. 9 and 15 (f_back, f_back^G), carrying A_b, and §4.2 (f_s^G).
    const glm::vec3 fBack = fibre.Ab * (mBack * backAzimuthal);
    const glm::vec3 fBackG = fibre.Ab * (mBackG * backAzimuthal);
    glm::vec3 fsG(0.0f);
    for (int p = 0; p < 3; ++p) {
        float b2 = std::max(parameters.beta[p] * parameters.beta[p], kMinVariance);
        glm::vec3 nG = forwardShare * fibre.nG[p] + (1.0f - forwardShare) * fibre.nGBack[p];
        fsG += nG * longitudinal(angles, parameters.alpha[p], b2 + spreadF + lobe);
    }
    // Zinke §5, F() without its single scattering T f_s (the caller's).
    const glm::vec3 scattered = glm::max(Tf - glm::vec3(T), glm::vec3(0.0f));
    return finiteNonNegative(T * db * fBack + df * scattered * (fsG + db * fBackG));
}

glm::vec3 dualScatteringUniformDome(const DualScatteringFibre& fibre, const DualScatteringDensities& densities) {
    const float db = std::clamp(finiteOr(densities.backward, 0.0f), 0.0f, 1.0f);
    return finiteNonNegative(db * fibre.Ab);
}

float multipleScatteringGain(const MarschnerParameters& parameters, const DualScatteringDensities& densities) {
    // Across the fibre (θ = 0).
    DualScatteringLobes lobes = dualScatteringLobesAt(parameters, 1.0f, 256);
    DualScatteringFibre fibre = dualScatteringFibre(lobes, parameters.alpha, parameters.beta, densities.backward);
    glm::vec3 single(0.0f);
    for (int p = 0; p < 3; ++p) single += lobes.forward[p] + lobes.backward[p];
    const float df = std::clamp(finiteOr(densities.forward, 0.0f), 0.0f, 1.0f);
    const float db = std::clamp(finiteOr(densities.backward, 0.0f), 0.0f, 1.0f);
    const float T = std::exp(-1.0f);
    float gain = 0.0f;
    for (int c = 0; c < 3; ++c) {
        float Tf = std::exp(-(1.0f - fibre.aF[c]));
        float added = T * db * fibre.Ab[c] +
                      df * std::max(Tf - T, 0.0f) * (fibre.aF[c] + kPiF * fibre.nGBack[0][c] +
                                                     kPiF * fibre.nGBack[1][c] + kPiF * fibre.nGBack[2][c] +
                                                     db * fibre.Ab[c]);
        float reference = T * single[c];
        if (reference > 1e-8f) gain = std::max(gain, added / reference);
        else if (added > 0.0f) gain = std::max(gain, 1e6f);
    }
    return finiteOr(gain, 0.0f);
}

}  // namespace hdhair
