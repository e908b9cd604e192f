// The dual scattering approximation (DualScattering.h): the fibre's
// attenuations against a numerical integration of the Marschner model over
// the sphere, the fibre quantities against the paper's equations evaluated
// here, the table against the analytic fibre, the light-path terms' limits
// (no fibre in front: no global term; nothing scatters back: no local term),
// and finite, bounded values at the hard cases (hdHair/shading/README.md,
// "Dual scattering", and docs/hard-cases.md).

#include <algorithm>
#include <cmath>
#include <random>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "hdHair/shading/DualScattering.h"
#include "hdHair/shading/Marschner.h"
#include "hdHair/shading/tests/FibreDirections.h"

using namespace hdhair;

namespace {

constexpr float kPi = 3.14159265358979323846f;

glm::vec3 direction(float theta, float phi) { return test::fibreDirection(theta, phi); }
using test::finiteNonNegative;

MarschnerParameters withMelanin(float melanin) {
    MarschnerParameters parameters;
    parameters.sigmaA = marschnerSigmaAFromMelanin(melanin);
    return parameters;
}

DualScatteringLobes lobesAt(const DualScatteringAttenuations& a, int node) {
    DualScatteringLobes lobes;
    for (int p = 0; p < 3; ++p) {
        lobes.forward[p] = a.forward[std::size_t(node) * 3 + p];
        lobes.backward[p] = a.backward[std::size_t(node) * 3 + p];
    }
    return lobes;
}

}  // namespace

// a_f,p and a_b,p are the energy the Marschner lobe p sends into the forward
// and backward halves: ∫ f_p(ωi, ωo) dωi over the light directions on the
// other side of the fibre (forward) or the eye's side (backward), by a 2D
// midpoint rule over the sphere. The d'Eon M integrates out exactly only on
// the whole θ_i range, so the bound is the quadrature's plus the clamped
// tails of the tilted lobes.
TEST(DualScattering, AttenuationsMatchIntegratedMarschner) {
    for (float melanin : {0.0f, 0.15f, 0.5f}) {
        MarschnerParameters parameters = withMelanin(melanin);
        const int nodes = 8;
        DualScatteringAttenuations attenuations = buildDualScatteringAttenuations(parameters, nodes, 256);
        for (int node : {0, 3, 7}) {
            float cosThetaR = (float(node) + 0.5f) / float(nodes);
            float thetaR = std::acos(cosThetaR);
            glm::vec3 t(1, 0, 0), wo = direction(thetaR, 0.0f);
            glm::vec3 forward[3] = {glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f)};
            glm::vec3 backward[3] = {glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f)};
            const int thetaSteps = 720, phiSteps = 256;
            for (int i = 0; i < thetaSteps; ++i) {
                float thetaI = -0.5f * kPi + (float(i) + 0.5f) * kPi / thetaSteps;
                float weight = std::cos(thetaI) * (kPi / thetaSteps) * (kPi / phiSteps);
                for (int k = 0; k < phiSteps; ++k) {
                    float phi = (float(k) + 0.5f) * kPi / phiSteps;  // [0, π]; doubled for the mirror half
                    MarschnerLobes lobes = evaluateMarschner(t, direction(thetaI, phi), wo, parameters);
                    glm::vec3* half = phi < 0.5f * kPi ? backward : forward;
                    half[0] += 2.0f * weight * lobes.R;
                    half[1] += 2.0f * weight * lobes.TT;
                    half[2] += 2.0f * weight * lobes.TRT;
                }
            }
            for (int p = 0; p < 3; ++p)
                for (int c = 0; c < 3; ++c) {
                    SCOPED_TRACE(::testing::Message() << "melanin " << melanin << " cos θ " << cosThetaR << " lobe " << p
                                                      << " channel " << c);
                    EXPECT_NEAR(attenuations.forward[std::size_t(node) * 3 + p][c], forward[p][c], 0.01f);
                    EXPECT_NEAR(attenuations.backward[std::size_t(node) * 3 + p][c], backward[p][c], 0.01f);
                }
        }
    }
}

// Energy: what the fibre sends forward and backward is at most what reaches
// it (the white furnace of Marschner.h), and a white fibre loses little.
TEST(DualScattering, AttenuationsConserveEnergy) {
    for (float melanin : {0.0f, 0.3f, 0.95f}) {
        DualScatteringAttenuations a = buildDualScatteringAttenuations(withMelanin(melanin), 16, 128);
        for (int node = 0; node < a.nodes; ++node) {
            glm::vec3 sum(0.0f);
            for (int p = 0; p < 3; ++p) sum += a.forward[std::size_t(node) * 3 + p] + a.backward[std::size_t(node) * 3 + p];
            for (int c = 0; c < 3; ++c) {
                EXPECT_LE(sum[c], 1.01f) << "melanin " << melanin << " node " << node;
                if (melanin == 0.0f) {
                    EXPECT_GE(sum[c], 0.85f) << "node " << node;
                }
            }
        }
    }
}

// The fibre quantities are Zinke's eqs. 11-17 with the lobes' weights; here
// evaluated by hand for one channel of simple attenuations.
TEST(DualScattering, FibreFollowsThePapersEquations) {
    DualScatteringLobes lobes;
    lobes.forward[0] = glm::vec3(0.02f);
    lobes.forward[1] = glm::vec3(0.5f);
    lobes.forward[2] = glm::vec3(0.08f);
    lobes.backward[0] = glm::vec3(0.03f);
    lobes.backward[1] = glm::vec3(0.01f);
    lobes.backward[2] = glm::vec3(0.16f);
    glm::vec3 alpha(-0.1f, 0.05f, 0.15f), beta(0.1f, 0.05f, 0.2f);
    DualScatteringFibre fibre = dualScatteringFibre(lobes, alpha, beta, 0.7f);
    const double af = 0.6, ab = 0.2;
    const double alphaF = (0.02 * -0.1 + 0.5 * 0.05 + 0.08 * 0.15) / af;
    const double alphaB = (0.03 * -0.1 + 0.01 * 0.05 + 0.16 * 0.15) / ab;
    const double betaF2 = (0.02 * 0.01 + 0.5 * 0.0025 + 0.08 * 0.04) / af;
    const double betaB2 = (0.03 * 0.01 + 0.01 * 0.0025 + 0.16 * 0.04) / ab;
    const double q = 1.0 - af * af;
    const double Ab = ab * af * af / q + ab * ab * ab * af * af / (q * q * q);
    const double deltaB = alphaB * (1.0 - 2.0 * ab * ab / (q * q)) + alphaF * (2.0 * q * q + 4.0 * af * af * ab * ab) / (q * q * q);
    const double sigmaB = (1.0 + 0.7 * af * af) *
                          (ab * std::sqrt(2.0 * betaF2 + betaB2) + ab * ab * ab * std::sqrt(2.0 * betaF2 + 3.0 * betaB2)) /
                          (ab + ab * ab * ab * (2.0 * std::sqrt(betaF2) + 3.0 * std::sqrt(betaB2)));
    EXPECT_NEAR(fibre.aF.x, af, 1e-6);
    EXPECT_NEAR(fibre.aB.x, ab, 1e-6);
    EXPECT_NEAR(fibre.alphaF.x, alphaF, 1e-6);
    EXPECT_NEAR(fibre.alphaB.x, alphaB, 1e-6);
    EXPECT_NEAR(fibre.betaF2.x, betaF2, 1e-6);
    EXPECT_NEAR(fibre.betaB2.x, betaB2, 1e-6);
    EXPECT_NEAR(fibre.Ab.x, Ab, 1e-6);
    EXPECT_NEAR(fibre.deltaB.x, deltaB, 1e-5);
    EXPECT_NEAR(fibre.sigmaB2.x, sigmaB * sigmaB, 1e-6);
    EXPECT_NEAR(fibre.nG[1].x, 0.5 / kPi, 1e-6);
}

// The table holds the fibre at its nodes (to half precision) and is linear
// between them.
TEST(DualScattering, TableHoldsTheFibreAtItsNodes) {
    MarschnerParameters parameters = withMelanin(0.15f);
    DualScatteringTable table = buildDualScatteringTable(parameters, 0.7f, 16);
    DualScatteringAttenuations attenuations = buildDualScatteringAttenuations(parameters, 16);
    for (int node : {0, 5, 15}) {
        DualScatteringFibre exact = dualScatteringFibre(lobesAt(attenuations, node), parameters.alpha, parameters.beta, 0.7f);
        DualScatteringFibre tabled = sampleDualScatteringTable(table, (float(node) + 0.5f) / 16.0f);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(tabled.aF[c], exact.aF[c], 1e-3f * std::max(1.0f, exact.aF[c]));
            EXPECT_NEAR(tabled.Ab[c], exact.Ab[c], 1e-3f * std::max(1.0f, exact.Ab[c]));
            EXPECT_NEAR(tabled.deltaB[c], exact.deltaB[c], 1e-3f);
            EXPECT_NEAR(tabled.sigmaB2[c], exact.sigmaB2[c], 1e-3f * std::max(1.0f, exact.sigmaB2[c]));
            EXPECT_NEAR(tabled.betaF2[c], exact.betaF2[c], 1e-4f);
        }
    }
    DualScatteringFibre between = sampleDualScatteringTable(table, 6.0f / 16.0f);
    DualScatteringFibre low = sampleDualScatteringTable(table, 5.5f / 16.0f);
    DualScatteringFibre high = sampleDualScatteringTable(table, 6.5f / 16.0f);
    EXPECT_NEAR(between.Ab.x, 0.5f * (low.Ab.x + high.Ab.x), 1e-6f);
    std::vector<std::uint16_t> layer = table.halfLayer(64, 16);
    EXPECT_EQ(layer.size(), std::size_t(64) * 16 * 4);
}

// The light path: with nothing in front (T = 1) only the local term acts and
// equals d_b f_back; with no back density, and nothing in front, nothing is
// added; the global term grows as light reaches x through fibres.
TEST(DualScattering, LightPathLimits) {
    MarschnerParameters parameters = withMelanin(0.15f);
    DualScatteringTable table = buildDualScatteringTable(parameters, 0.7f);
    glm::vec3 t(1, 0, 0), wi = direction(0.1f, 2.5f), wo = direction(-0.05f, 0.0f);
    DualScatteringFibre fibre = sampleDualScatteringTable(table, std::cos(0.05f));
    DualScatteringDensities noBack{0.7f, 0.0f};
    glm::vec3 none = evaluateDualScattering(t, wi, wo, parameters, fibre, 1.0f, noBack);
    EXPECT_EQ(none, glm::vec3(0.0f));
    DualScatteringDensities densities;
    glm::vec3 front = evaluateDualScattering(t, wi, wo, parameters, fibre, 1.0f, densities);
    EXPECT_GT(front.x, 0.0f);
    glm::vec3 inside = evaluateDualScattering(t, wi, wo, parameters, fibre, std::exp(-2.0f), densities);
    // At T = e^-2 the local term is e^-2 of the front's; the global adds to it.
    for (int c = 0; c < 3; ++c) EXPECT_GT(inside[c], std::exp(-2.0f) * front[c]);
    // The uniform dome's local term is d_b ∫ f_back dωi = d_b A_b: check
    // against the integral of the T = 1 term over the sphere.
    glm::vec3 integral(0.0f);
    const int thetaSteps = 360, phiSteps = 360;
    for (int i = 0; i < thetaSteps; ++i) {
        float thetaI = -0.5f * kPi + (float(i) + 0.5f) * kPi / thetaSteps;
        for (int k = 0; k < phiSteps; ++k) {
            float phi = (float(k) + 0.5f) * 2.0f * kPi / phiSteps;
            integral += std::cos(thetaI) * (kPi / thetaSteps) * (2.0f * kPi / phiSteps) *
                        evaluateDualScattering(t, direction(thetaI, phi), wo, parameters, fibre, 1.0f, densities);
        }
    }
    glm::vec3 dome = dualScatteringUniformDome(fibre, densities);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(integral[c], dome[c], 0.02f * dome[c] + 1e-5f) << "channel " << c;
}

// Hard cases (docs/hard-cases.md): zero and huge absorption, T = 0 and 1,
// grazing and parallel directions, zero vectors: finite, non-negative, and
// bounded by what a white fibre at full density could add.
TEST(DualScattering, HardCasesStayFiniteAndBounded) {
    std::mt19937 random(2008);
    std::normal_distribution<float> gaussian;
    auto randomDirection = [&] { return glm::vec3(gaussian(random), gaussian(random), gaussian(random)); };
    for (glm::vec3 sigmaA : {glm::vec3(0.0f), glm::vec3(1e6f), glm::vec3(0.0f, 1.0f, 1e6f)}) {
        MarschnerParameters parameters;
        parameters.sigmaA = sigmaA;
        DualScatteringTable table = buildDualScatteringTable(parameters, 1.0f, 16);
        for (float cosTheta : {0.0f, 0.001f, 0.5f, 1.0f}) {
            DualScatteringFibre fibre = sampleDualScatteringTable(table, cosTheta);
            EXPECT_TRUE(finiteNonNegative(fibre.Ab));
            EXPECT_TRUE(finiteNonNegative(fibre.sigmaB2));
            EXPECT_TRUE(std::isfinite(fibre.deltaB.x));
            for (float T : {0.0f, 1e-30f, 0.5f, 1.0f, std::nanf("")}) {
                for (int i = 0; i < 200; ++i) {
                    glm::vec3 t = randomDirection(), wi = randomDirection(), wo = randomDirection();
                    if (i == 0) wi = t;                    // light along the fibre
                    if (i == 1) wo = -t;                   // eye along the fibre
                    if (i == 2) wi = glm::vec3(0.0f);      // no direction
                    if (i == 3) t = glm::vec3(0.0f);       // zero-length segment
                    glm::vec3 added = evaluateDualScattering(t, wi, wo, parameters, fibre, T, {1.0f, 1.0f}, 0.0f);
                    ASSERT_TRUE(finiteNonNegative(added)) << "σ_a " << sigmaA.x << " T " << T << " case " << i;
                    // M_dEon peaks below 1/(π v) ≈ 1/(4π σ²) for the narrowest
                    // lobe: a generous cap that a blow-up would cross.
                    for (int c = 0; c < 3; ++c) ASSERT_LT(added[c], 1e3f);
                }
            }
        }
        if (sigmaA.x >= 1e6f) {
            // Nothing passes through the fibre: only its surface (R) scatters.
            DualScatteringFibre fibre = sampleDualScatteringTable(table, 0.9f);
            EXPECT_LT(fibre.nG[1].x + fibre.nG[2].x, 1e-6f);
            EXPECT_NEAR(fibre.aF.x, kPi * fibre.nG[0].x, 1e-3f);
        }
    }
}

// multipleScattering=auto's measure: large for blond, small for black, and
// zero gain where nothing scatters back or forward.
TEST(DualScattering, GainOrdersByAbsorption) {
    DualScatteringDensities densities;
    float black = multipleScatteringGain(withMelanin(0.95f), densities);
    float brown = multipleScatteringGain(withMelanin(0.5f), densities);
    float blond = multipleScatteringGain(withMelanin(0.15f), densities);
    float white = multipleScatteringGain(withMelanin(0.0f), densities);
    RecordProperty("black", std::to_string(black));
    RecordProperty("brown", std::to_string(brown));
    RecordProperty("blond", std::to_string(blond));
    std::printf("gain: white %.4f blond %.4f brown %.4f black %.4f\n", white, blond, brown, black);
    EXPECT_LT(black, brown);
    EXPECT_LT(brown, blond);
    EXPECT_LE(blond, white);
    EXPECT_EQ(multipleScatteringGain(withMelanin(0.15f), {0.0f, 0.0f}), 0.0f);
}
