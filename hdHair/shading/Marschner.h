#pragma once
// Marschner hair scattering on the CPU: the analytic reference for the tabled
// path (MarschnerTables.h) and for shaders/include/marschner.glsl.
//
// Marschner, Jensen, Cammarano, Worley & Hanrahan 2003, "Light Scattering
// from Human Hair Fibers" (SIGGRAPH), with the longitudinal function of
// d'Eon, Francois, Hill, Letteri & Aubry 2011, "An Energy-Conserving Hair
// Reflectance Model" (EGSR), §4. hdHair/shading/README.md has the derivation
// notes, the parameter table and the measurements quoted here.
//
// Geometry (Marschner §2.2, Fig. 2). t is the fibre tangent, root to tip; ωi
// points towards the light, ωr (ωo) towards the eye.
//   θ_i, θ_r  inclinations from the normal plane: sin θ = t·ω, θ ∈ [−π/2, π/2]
//   φ_i, φ_r  azimuths in the normal plane;  φ = φ_r − φ_i (only |φ| matters
//             for a round fibre, so φ ∈ [0, π] here)
//   θ_h = (θ_i + θ_r)/2,  θ_d = (θ_r − θ_i)/2
//
// Scattering function, Marschner eq. (2) (Woodhouse eq. 2.6):
//   S(ωi, ωr) = Σ_p M_p(θ_i, θ_r) N_p(η'(η, θ_d); φ) / cos²θ_d,  p ∈ {R=0, TT=1, TRT=2}
// and the radiance scattered towards the eye, Marschner eq. (1) with the fibre
// diameter D folded into the light's units:
//   L_r(ωr) = ∫ S(ωi, ωr) L_i(ωi) cos θ_i dωi,
// so a light of irradiance E from ωi contributes E · S · cos θ_i.
//
// Longitudinal M_p. Marschner uses a unit-area Gaussian g(β_p; θ_h − α_p).
// Measured (README, "Where we depart"): with the 1/cos²θ_d of eq. (2)
// that Gaussian integrates to 0.17 .. 3.2 instead of 1 over the sphere of ωi
// (grazing θ_r, tilted lobes), so a white furnace would exceed 1 threefold.
// We therefore use d'Eon 2011's energy-conserving longitudinal function,
//   M_dEon(θ_i, θ_r') = csch(1/v)/(2v) · exp(−sin θ_i sin θ_r'/v) · I0(cos θ_i cos θ_r'/v),
// which satisfies ∫ M_dEon cos θ_i dθ_i = 1 for every θ_r'. The cuticle tilt
// α_p is applied by rotating the outgoing inclination, θ_r' = θ_r − 2α_p (as
// pbrt-v4 does), which puts the lobe's peak at θ_h = α_p exactly (the function
// is even in θ_h − α_p along θ_d = 0). v_p = (2β_p)²: for small v, M_dEon is a
// Gaussian in θ_i + θ_r = 2θ_h of variance v, i.e. Marschner's Gaussian of
// standard deviation β_p in θ_h. In the form of eq. (2) this is
//   M_p = M_dEon(θ_i, θ_r − 2α_p) · cos²θ_d / cos θ_i,
// which equals Marschner's smooth-fibre limit δ(θ_i + θ_r) on the specular cone
// (where cos θ_i = cos θ_d). I0 is evaluated in log space for v ≤ 0.1.
//
// Azimuthal N_p (Marschner §3.2, eqs. 3–10, Appendix B):
//   N_p(p, φ) = Σ_roots A(p, h) · |2 dφ/dh (p, h)|⁻¹                       eq. (8)
//   φ(p, h) = 2pγ_t − 2γ_i + pπ, h = sin γ_i, sin γ_t = h/η'               eq. (3)
//     approximated by the cubic of eq. (10), c = asin(1/η'):
//   φ(p, γ_i) ≈ (6pc/π − 2) γ_i − 8pc γ_i³/π³ + pπ
//   A(0, h) = F                                                           eq. (5)
//   A(p, h) = (1 − F)² F^(p−1) T(σ_a', h)^p,  p ≥ 1                       eqs. (6), (9)
//   Bravais index η' = √(η² − sin²θ)/cos θ (Appendix B) for the in-plane
//       geometry (γ_t, c); η'' = η²/η' is not used, see F.
//   F: the exact unpolarised Fresnel factor of η at the true 3D angle of
//       incidence ξ, cos ξ = cos θ cos γ_i (as d'Eon 2011 and pbrt do). With
//       Appendix B's split F = (F_s(η') + F_p(η''))/2, η'' drops below 1 at
//       grazing θ and F_p gets an artificial total-reflection edge; measured,
//       it kept the tables' error from converging (N error 0.15 at 256²).
//       The exit factors of eq. (9) equal the entry one by Fresnel
//       reciprocity, so Σ_p A(p, h) ≤ 1 for every h.
//   T(σ_a', h) = exp(−σ_a' · 2 cos γ_t), σ_a' = σ_a / cos θ_t, sin θ_t = sin θ/η.
//       2 cos γ_t is the chord of the unit-radius cross-section. The printed
//       eq. (7) reads exp(−2σ_a(1 + cos 2γ_t)) = exp(−4σ_a cos²γ_t), which is not
//       that chord; we use the geometric chord, as d'Eon 2011 and pbrt do,
//       because the colour → σ_a inversion below is fitted with it.
// Which inclination θ: Marschner evaluates η', F and σ_a' at θ_d. We use θ_r
// for all three lobes (as pbrt-v4 does with θ_o): on the smooth fibre's
// specular cone |θ_d| = |θ_r|, and with one θ per ωo the lobes share a
// Fresnel split, so Σ_p ∫ N_p dφ ≤ 1 and the white furnace cannot exceed 1.
// Measured alternatives (README): θ_d gives 0.64 .. 1.10 with the default
// tilts; θ_d + α_p gives 0.45 .. 1.09; θ_r gives 0.86 .. 0.996.
// All roots of φ(p, γ) ≡ φ (mod 2π) with |γ_i| ≤ π/2 are summed, so
// ∫ N_p dφ = ½∫ A(p, h) dh exactly (the change of variables of eq. 8).
// |dφ/dγ| is clamped at kMarschnerMinDPhiDGamma to keep caustics finite.
//
// TRT caustic (Marschner §4.3 "Approximating the caustic" and Table 1):
//   for η' < 2: h_c = sin γ_c with dφ/dγ(2, γ_c) = 0, φ_c = φ(2, γ_c), t = 1,
//               Δh = min(Δh_M, 2√(2 w_c / |∂²φ/∂h²(h_c)|));
//   for η' ≥ 2: h_c = 0, φ_c = 0, Δh = Δh_M, t fades 1 → 0 over η' ∈ [2, 2 + Δη'];
//   N_TRT(φ) = N_p(2, φ) · (1 − t g(w_c; φ − φ_c)/g(w_c; 0)) (1 − t g(w_c; φ + φ_c)/g(w_c; 0))
//            + t k_G A(2, h_c) Δh (g(w_c; φ − φ_c) + g(w_c; φ + φ_c)).
// The smooth glint lobes replace the infinite caustic; k_G ≤ ~1 keeps the
// white furnace within its tolerance (k_G = 5 adds up to ~0.2 of energy).
//
// Cross-section eccentricity a ≠ 1 (Marschner §4.4) is NOT modelled: the
// fibre is round, N depends only on |φ|, and `eccentricity` is ignored.
// Reciprocity: f = S cos θ_i is unchanged when ωi and ωo swap, for every lobe,
// on the specular cone θ_i = −θ_r when α_p = 0 (M_dEon is symmetric and
// |θ_i| = |θ_r| there). Off the cone N_p's use of θ_r (energy first) and the
// tilt break it: README gives the measured f-weighted differences.

#include <glm/vec3.hpp>

namespace hdhair {

// |dφ/dγ| below this counts as this (caustics, η' near 1 for TT): bounds N_p
// by A/(2·kMarschnerMinDPhiDGamma) = 500·A.
constexpr double kMarschnerMinDPhiDGamma = 1e-3;

constexpr float kMarschnerDegrees = 0.017453292519943295f;  // radians per degree

// Published defaults (Marschner 2003, Table 1). Angles in radians.
struct MarschnerParameters {
    float eta = 1.55f;  // η, index of refraction of the fibre (keratin), >= 1 (values below 1 count as 1)
    // Longitudinal shifts α_p (cuticle tilt), θ positive towards the tip.
    // Table 1: α_R −10° .. −5°, α_TT = −α_R/2, α_TRT = −3α_R/2.
    glm::vec3 alpha{-7.5f * kMarschnerDegrees, 3.75f * kMarschnerDegrees, 11.25f * kMarschnerDegrees};
    // Longitudinal widths β_p (standard deviation in θ_h). Table 1: β_R 5° .. 10°,
    // β_TT = β_R/2, β_TRT = 2β_R. Values below 0.5° count as 0.5°.
    glm::vec3 beta{7.5f * kMarschnerDegrees, 3.75f * kMarschnerDegrees, 15.0f * kMarschnerDegrees};
    // σ_a, absorption coefficient per RGB channel in units of 1/fibre radius
    // (Table 1: 0.2 .. ∞ per diameter). Use marschnerSigmaAFrom*() below.
    // Default: brown, Woodhouse §2.2.3 / Sadeghi 2010 (0.3, 0.6, 1.2) per diameter.
    glm::vec3 sigmaA{0.15f, 0.3f, 0.6f};
    float eccentricity = 1.0f;  // a; Table 1: 0.85 .. 1. Only 1 (round) is modelled; ignored.
    // Glints / TRT caustic (§4.3, Table 1).
    float glintScale = 1.0f;                        // k_G, Table 1: 0.5 .. 5 (1: measured near energy-neutral)
    float causticWidth = 15.0f * kMarschnerDegrees;  // w_c, Table 1: 10° .. 25°
    float causticFade = 0.3f;                        // Δη', Table 1: 0.2 .. 0.4
    float causticLimit = 0.5f;                       // Δh_M, Table 1: 0.5
};

// Fills the TT and TRT shifts and widths from the R ones as Table 1 does.
MarschnerParameters marschnerParametersFromR(float alphaR, float betaR);

// v_p = (2β_p)², the variance of d'Eon's M_p that matches a Gaussian of
// standard deviation β_p in θ_h (clamped to β ≥ 0.5°).
float marschnerLongitudinalVariance(float beta);

// σ_a from a colour, the d'Eon/Chiang inversion (Chiang, Bitterli, Tappan &
// Burley 2016, "A Practical and Controllable Hair and Fur Model for
// Production Path Tracing", §4.2, eq. 9; pbrt-v4 SigmaAFromReflectance):
//   σ_a = (ln c / (5.969 − 0.215β_n + 2.532β_n² − 10.73β_n³ + 5.574β_n⁴ + 0.245β_n⁵))²
// c is the multiple-scattering albedo the hair should show (linear RGB, each
// channel clamped to [1e-4, 1]); β_n is Chiang's azimuthal roughness in [0, 1]
// that the fit assumes (0.3 ≈ pbrt's default). The fit is for Chiang's model
// with all orders p; used with this 3-lobe model it gives the right hue and
// ordering, not the exact albedo.
glm::vec3 marschnerSigmaAFromColor(const glm::vec3& color, float azimuthalRoughness = 0.3f);
// The exact inverse of the formula above (for round trips and UIs).
glm::vec3 marschnerColorFromSigmaA(const glm::vec3& sigmaA, float azimuthalRoughness = 0.3f);
// σ_a = C_eu (0.419, 0.697, 1.37) + C_pheo (0.187, 0.4, 1.05)
// (d'Eon 2011 §6.1; Chiang 2016 eq. 8), concentrations >= 0.
glm::vec3 marschnerSigmaAFromConcentration(float eumelanin, float pheomelanin);
// melanin in [0, 1] → total concentration −ln(1 − melanin) (clamped at
// melanin 0.9999), split by redness in [0, 1] into pheomelanin (redness) and
// eumelanin (1 − redness): Blender Cycles' Principled Hair mapping. melanin 0
// gives σ_a = 0 (white), 1 near black.
glm::vec3 marschnerSigmaAFromMelanin(float melanin, float redness = 0.0f);

// The angles of a configuration. Zero or non-finite vectors count as
// perpendicular to everything (like evaluateKajiyaKay); a direction parallel to
// t has no azimuth and gets φ = 0.
struct MarschnerAngles {
    float sinThetaI = 0.0f, cosThetaI = 1.0f;
    float sinThetaR = 0.0f, cosThetaR = 1.0f;
    float phi = 0.0f;        // |φ_r − φ_i| ∈ [0, π]
    float sinThetaD = 0.0f;  // sin θ_d ∈ [−1, 1], θ_d = (θ_r − θ_i)/2
    float cosThetaD = 1.0f;
};
MarschnerAngles marschnerAngles(const glm::vec3& t, const glm::vec3& wi, const glm::vec3& wo);

// d'Eon's M_dEon(θ_i, θ_r − 2α) with variance v (see above); >= 0, finite.
float marschnerLongitudinal(float sinThetaI, float cosThetaI, float sinThetaR, float cosThetaR, float alpha,
                            float variance);

// N_p(φ) for p = 0 (R), 1 (TT), 2 (TRT, with the caustic treatment), solving
// the cubic's roots on every call. phi ∈ [0, π] (|φ| of any angle is used),
// cosTheta = cos θ_r ∈ [0, 1]. Finite, >= 0.
glm::vec3 marschnerAzimuthal(int p, float phi, float cosTheta, const MarschnerParameters& parameters);

// A(p, h) of eqs. (5), (6), (9): the attenuation of path p at offset h ∈ [−1, 1]
// with the N_p setup at inclination cos θ (σ_a' = σ_a / cos θ_t, η', F at
// cos ξ = cos θ cos γ_i). Finite, in [0, 1].
glm::vec3 marschnerAttenuation(int p, float h, float cosTheta, const MarschnerParameters& parameters);

struct MarschnerLobes {
    // f_p = S_p · cos θ_i = M_dEon_p · N_p: the radiance towards ωo per unit
    // irradiance from ωi (multiply by the light's irradiance, as with
    // evaluateKajiyaKay's terms). Finite and >= 0 for every input.
    glm::vec3 R{0.0f}, TT{0.0f}, TRT{0.0f};
    // S = Σ_p M_p N_p / cos²θ_d (eq. 2) = (R + TT + TRT)/cos θ_i, with cos θ_i
    // clamped at 1e-4 (S grows as 1/cos θ_i towards light along the fibre).
    glm::vec3 S{0.0f};
    glm::vec3 radiance() const { return R + TT + TRT; }
};

// The analytic model: roots solved per call (reference; slow).
MarschnerLobes evaluateMarschner(const glm::vec3& t, const glm::vec3& wi, const glm::vec3& wo,
                                 const MarschnerParameters& parameters);

// Combines azimuthal values (analytic or tabled) with the longitudinal terms.
MarschnerLobes combineMarschnerLobes(const MarschnerAngles& angles, const glm::vec3& nR, const glm::vec3& nTT,
                                     const glm::vec3& nTRT, const MarschnerParameters& parameters);

}  // namespace hdhair
