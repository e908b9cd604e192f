#pragma once
// A Gaussian spherical radial basis function (SRBF) light, the unit in which
// Ren et al. 2010 ("Interactive Hair Rendering Under Environment Lighting",
// §3, Eq. 2) write an environment: L(ω) ≈ Σ_j L_j G(ω; ξ_j, λ_j) with
//   G(ω; ξ, λ) = exp(−λ) exp(λ (ω·ξ)) = exp(λ (ω·ξ − 1)).
// G peaks at 1 on its centre ξ and is not normalised, so an SRBF's
// amplitude L_j is the radiance it adds along ξ (digest 002, §2.1, §9.2).
// For large λ, G ≈ exp(−λ θ²/2): an angular standard deviation of 1/√λ
// (14.3° at λ = 16, 7.2° at λ = 64).
// Nothing here truncates the kernel: the paper zeroes it below 10⁻³ in its
// shadow pass (§2.2 of the digest), which is a matter for whoever draws
// the lights, not for the representation; srbfSupportCosine() gives that
// cut-off.
// This is the one definition of the kernel, its bounds and its integral:
// the fit (here), the convolution tables (hdHair/shading) and the renderer
// all use it, in the direction the data flows (scene → environment →
// shading).

#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace hdhair {

// The paper's bounds on the bandwidth (§7, "SRBF Light Approximation"):
// wider lobes (λ < 16) make the effective-transmittance approximation poor,
// narrower ones (λ > 64) need too many lights.
constexpr float kMinSrbfBandwidth = 16.0f;
constexpr float kMaxSrbfBandwidth = 64.0f;

// The shape of one SRBF, without its amplitude: what the convolution tables
// are indexed by.
struct SrbfLobe {
    glm::vec3 centre{0.0f, 1.0f, 0.0f};  // ξ, unit length: radiance comes *from* ξ, like ωi
    float bandwidth = kMinSrbfBandwidth;  // λ > 0
};

// One fitted SRBF light: its lobe and its amplitude.
struct Srbf {
    SrbfLobe lobe;
    glm::vec3 amplitude{0.0f};  // L_j, linear RGB radiance (non-negative)
};

// G(ω; ξ, λ) for unit ω and ξ, in float (the fit, the renderer) or double
// (the tables' numerical reference).
template <typename Real>
Real srbfKernel(const glm::vec<3, Real>& direction, const glm::vec<3, Real>& centre, Real bandwidth) {
    return std::exp(bandwidth * (glm::dot(direction, centre) - Real(1)));
}

inline double srbfKernel(const SrbfLobe& lobe, const glm::dvec3& direction) {
    return srbfKernel(direction, glm::dvec3(lobe.centre), double(lobe.bandwidth));
}

// The sum Σ_j L_j G(ω; ξ_j, λ_j) along the unit direction ω.
glm::vec3 srbfRadiance(const std::vector<Srbf>& srbfs, const glm::vec3& direction);

// ∫ G dω over the sphere, 2π (1 − e^{−2λ}) / λ: the solid angle an SRBF of
// amplitude 1 is worth (0.393 sr at λ = 16, 0.098 sr at λ = 64), and the
// irradiance (normal to ξ) of the distant light a lobe becomes as λ → ∞.
template <typename Real>
Real srbfIntegral(Real bandwidth) {
    constexpr Real twoPi = Real(6.283185307179586);
    return twoPi * -std::expm1(Real(-2) * bandwidth) / bandwidth;
}

// cos α of the angle α beyond which G < 10⁻³, the paper's cut-off:
// 1 − ln(1000) / λ.
float srbfSupportCosine(float bandwidth);

}  // namespace hdhair
