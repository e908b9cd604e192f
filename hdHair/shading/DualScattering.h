#pragma once
// Multiple scattering in hair by the dual scattering approximation: Zinke,
// Yuksel, Weber & Keyser 2008, "Dual Scattering Approximation for Fast
// Multiple Scattering in Hair" (SIGGRAPH 2008), §4 (the approximation) and
// §5 (its real-time form with opacity maps); Ren, Zhou, Li, Hua & Guo 2010
// §3.2 and §6 for SRBF lights. The CPU mirror of shaders/include/
// dualScattering.glsl, formula for formula; hdHair/shading/README.md
// ("Dual scattering") gives the choices and the measurements behind them.
//
// Light reaching a fibre x inside a groom has either come straight from the
// light (the shadow transmittance T of the deep opacity maps) or been
// scattered forward by the fibres in between (the global term), and light
// that passed x comes back from the fibres behind it (the local term):
//
//   f_dual = T (f_s + d_b f_back) + d_f (T_f − T) (f_s^G + d_b f_back^G)   (Zinke §5, F())
//
// f_s is Marschner's single scattering (Marschner.h), d_f and d_b the
// density factors (Zinke §4; 0.6 .. 0.8 for human hair, Ren §3.2). Zinke's
// F() has π d_b f_back^G: in his normalisation of f_back; in ours (below,
// each term carrying the energy its derivation gives it) the π goes.
//
// Fibre quantities, from the azimuthal terms N_p (p = R, TT, TRT) at the
// inclination θ of the table row:
//   a_f,p(θ) = ∫_{π/2<|φ|≤π} N_p(φ, θ) dφ, a_b,p(θ) = ∫_{|φ|<π/2} N_p dφ: each
//     lobe's forward and backward scattering attenuation (eqs. 6 and 12, with
//     d'Eon's M, whose ∫ M cos θ_i dθ_i = 1, integrated out);
//   ā_f = Σ_p a_f,p, ā_b = Σ_p a_b,p;
//   α_f = Σ_p a_f,p α_p / ā_f, β_f² = Σ_p a_f,p β_p² / ā_f, and α_b, β_b² alike
//     (eqs. 13 and 14: the lobes' shifts and widths weighted by their energy);
//   A_b = A_1 + A_3, A_1 = ā_b ā_f²/(1 − ā_f²), A_3 = ā_b³ ā_f²/(1 − ā_f²)³
//     (eqs. 11, 13, 14: one and three backward events);
//   Δ_b = α_b (1 − 2ā_b²/(1 − ā_f²)²) + α_f (2(1 − ā_f²)² + 4ā_f²ā_b²)/(1 − ā_f²)³ (eq. 16);
//   σ_b = (1 + d_b ā_f²)(ā_b √(2β_f² + β_b²) + ā_b³ √(2β_f² + 3β_b²))
//         / (ā_b + ā_b³ (2β_f + 3β_b))                                        (eq. 17);
//   N^G_p = (2/π) ∫_{π/2}^{π} N_p dφ = a_f,p/π: the azimuthal term averaged
//     over the forward half (§4.2), and a_b,p/π, over the backward half.
// Light path quantities, from the deep opacity maps (Zinke §5 counts the
// fibres n in front of x with an opacity map): T = exp(−k Ω) is the
// probability that no fibre intercepted the light, so n = −ln T (k = 1, the
// fibres' projected area as optical depth, DeepOpacityLayers.h) is the
// expected number intercepted, and with the count Poisson-distributed
//   T_f = E[ā_f^N] = exp(−n (1 − ā_f)) = T^(1 − ā_f)     (eq. 6's product, averaged)
//   σ̄_f² = n β_f²                                        (eq. 7)
// T_f − T is the light that reached x after at least one forward event.
// The longitudinal functions: Zinke's g(θ_h − shift, σ²)/cos²θ_d in
// Marschner's form becomes d'Eon's M(θ_i, θ_r; shift, v = 4σ²) here, the same
// map that takes Marschner's single scattering to ours (Marschner.h), whose
// ∫ M cos θ_i dθ_i = 1 makes each term's energy its azimuthal integral.
// The azimuthal functions, at φ between the eye and the light:
//   f_back  = A_b M(Δ_b, σ_b²) (π − φ)/π²     f_back^G = A_b M(Δ_b, σ_b² + σ̄_f²) (π − φ)/π²   (eqs. 9, 15)
//   f_s^G   = Σ_p M(α_p, β_p² + σ̄_f²) (φ/π · a_f,p/π + (1 − φ/π) a_b,p/π)                 (§4.2)
// all per unit irradiance from the light, as Marschner's f_p. What comes
// back (A_b of the light that passed x) leaves towards the light's side,
// spread linearly in azimuth so that it carries exactly A_b (Zinke spreads
// it over a half circle, an edge at φ = π/2). The light scattered forward to
// x arrives over the half circle about the light; x's lobes averaged over
// that half circle, seen at φ, take a share φ/π of each lobe's forward half
// and the rest of its backward half, each half's energy spread evenly.
// At φ = π this is Zinke's N^G_p; unlike it, it carries ā_f + ā_b in total,
// not 2ā_f, and does not show a blond fibre's forward scattering (ā_f ten
// times ā_b) to an eye beside the light (measured: hdHair/shading/README.md,
// "Dual scattering").
//
// SRBF lights (Ren 2010 eqs. 6-7): a lobe counts as a distant light from its
// centre ξ, T_f and σ̄_f taken there, and its width adds to the first
// event's spread: a lobe of bandwidth λ has angular variance 1/λ about ξ,
// 1/(4λ) in θ_h.

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "hdHair/shading/Marschner.h"

namespace hdhair {

// d_f and d_b as Zinke's examples and Ren 2010 use them.
constexpr float kDualScatteringDensity = 0.7f;
// ā_f and ā_b are clamped below 1 so that 1/(1 − ā_f²) stays finite; a
// fibre's albedo is below 1 anyway (white furnace 0.86 .. 0.996).
constexpr float kDualScatteringMaxAttenuation = 0.99f;

struct DualScatteringDensities {
    float forward = kDualScatteringDensity;   // d_f
    float backward = kDualScatteringDensity;  // d_b
};

// a_f,p and a_b,p per lobe at `nodes` inclinations cos θ = (j + ½)/nodes,
// the Marschner tables' t axis.
struct DualScatteringAttenuations {
    int nodes = 0;
    std::vector<glm::vec3> forward;   // 3 a node: R, TT, TRT
    std::vector<glm::vec3> backward;  // 3 a node
};

// From the analytic azimuthal terms, by the midpoint rule over φ with
// `azimuths` points a half.
DualScatteringAttenuations buildDualScatteringAttenuations(const MarschnerParameters& parameters, int nodes = 64,
                                                           int azimuths = 256);

struct DualScatteringLobes {
    glm::vec3 forward[3];   // a_f,p
    glm::vec3 backward[3];  // a_b,p
};

// The fibre's quantities at one inclination (the header's list).
struct DualScatteringFibre {
    glm::vec3 aF{0.0f}, aB{0.0f};            // ā_f, ā_b
    glm::vec3 alphaF{0.0f}, alphaB{0.0f};    // α_f, α_b (radians)
    glm::vec3 betaF2{0.0f}, betaB2{0.0f};    // β_f², β_b²
    glm::vec3 Ab{0.0f}, deltaB{0.0f}, sigmaB2{0.0f};  // A_b, Δ_b, σ_b²
    glm::vec3 nG[3] = {glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f)};      // N^G_p: a_f,p/π
    glm::vec3 nGBack[3] = {glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f)};  // a_b,p/π
};
DualScatteringFibre dualScatteringFibre(const DualScatteringLobes& lobes, const glm::vec3& alpha,
                                        const glm::vec3& beta, float backwardDensity);

// What the GPU reads: the fibre at each node, the quantities the shading
// needs, rounded to half as uploaded. One layer of the material tables'
// texture array (MarschnerTables.h), texel (q, j) holding quantity q at node
// j, RGB:
//   q = 0 ā_f, 1 A_b, 2 Δ_b, 3 σ_b², 4 β_f², 5..7 N^G_R, N^G_TT, N^G_TRT,
//   8..10 a_b,p/π for R, TT, TRT.
// The shader samples it at s = (q + ½)/width, t = cos θ: bilinear there is
// linear in cos θ between nodes, clamped at the end nodes.
constexpr int kDualScatteringQuantities = 11;
struct DualScatteringTable {
    int nodes = 0;
    std::vector<glm::vec3> values;  // kDualScatteringQuantities a node, node-major
    // The layer as RGBA halves, width × height (width >= the quantities,
    // height == nodes), unused texels 0.
    std::vector<std::uint16_t> halfLayer(int width, int height) const;
};
DualScatteringTable buildDualScatteringTable(const MarschnerParameters& parameters, float backwardDensity,
                                             int nodes = 64);

// The table's fibre at cos θ, as dualScattering.glsl reads it (only the
// quantities the table holds are set).
DualScatteringFibre sampleDualScatteringTable(const DualScatteringTable& table, float cosTheta);

// The radiance towards ωo that multiple scattering adds per unit
// irradiance from ωi (unshadowed), at shadow transmittance T from that
// light: f_dual − T f_s. `lobeVariance`: an SRBF lobe's 1/(4λ), else 0.
// Finite and >= 0 for every input.
glm::vec3 evaluateDualScattering(const glm::vec3& t, const glm::vec3& wi, const glm::vec3& wo,
                                 const MarschnerParameters& parameters, const DualScatteringFibre& fibre,
                                 float transmittance, const DualScatteringDensities& densities,
                                 float lobeVariance = 0.0f);

// What a uniform dome of radiance 1 adds, unshadowed (T = 1, so only the
// local term): d_b ∫ f_back dωi = d_b A_b.
glm::vec3 dualScatteringUniformDome(const DualScatteringFibre& fibre, const DualScatteringDensities& densities);

// How much light dual scattering adds to a fibre's single scattering, as a
// ratio of energies over the sphere of eye directions, for a fibre seen and
// lit across (θ = 0) one fibre deep (T = e^−1): the largest channel of
//   (T d_b A_b + d_f (T^(1−ā_f) − T)(ā_f + ā_b + d_b A_b)) / (T (ā_f + ā_b)).
// multipleScattering=auto skips materials under kMultipleScatteringBound.
float multipleScatteringGain(const MarschnerParameters& parameters, const DualScatteringDensities& densities);
// The gain below which multiple scattering changes a frame by less than 10 %
// of its light: the gain tracks the light Cycles' later bounces add
// (hdHair/shading/README.md, "Where multiple scattering pays").
constexpr float kMultipleScatteringBound = 0.10f;

}  // namespace hdhair
