#pragma once
// A Gaussian spherical radial basis function (SRBF) light, the unit in which
// Ren et al. 2010 ("Interactive Hair Rendering Under Environment Lighting",
// §3, Eq. 2) write an environment: L(ω) ≈ Σ_j L_j G(ω; ξ_j, λ_j) with
//   G(ω; ξ, λ) = exp(−λ) exp(λ (ω·ξ)) = exp(λ (ω·ξ − 1)).
// G peaks at 1 on its centre ξ and is not normalised, so an SRBF's
// amplitude L_j is the radiance it adds along ξ (digest 002, §2.1, §9.2).
// Nothing here truncates the kernel: the paper zeroes it below 10⁻³ in its
// shadow pass (§2.2 of the digest), which is a matter for whoever draws
// the lights, not for the representation; srbfSupportCosine() gives that
// cut-off.

#include <vector>

#include <glm/vec3.hpp>

namespace hdhair {

// The paper's bounds on the bandwidth (§7, "SRBF Light Approximation"):
// wider lobes (λ < 16) make the effective-transmittance approximation poor,
// narrower ones (λ > 64) need too many lights.
constexpr float kMinSrbfBandwidth = 16.0f;
constexpr float kMaxSrbfBandwidth = 64.0f;

struct Srbf {
    glm::vec3 centre{0.0f, 1.0f, 0.0f};  // ξ, unit length
    float bandwidth = kMinSrbfBandwidth;  // λ
    glm::vec3 amplitude{0.0f};            // L_j, linear RGB radiance (non-negative)
};

// G(ω; ξ, λ) for unit ω and ξ.
float srbfKernel(const glm::vec3& direction, const glm::vec3& centre, float bandwidth);

// The sum Σ_j L_j G(ω; ξ_j, λ_j) along the unit direction ω.
glm::vec3 srbfRadiance(const std::vector<Srbf>& srbfs, const glm::vec3& direction);

// ∫ G dω over the sphere, 2π (1 − e^{−2λ}) / λ: the solid angle an SRBF of
// amplitude 1 is worth (0.393 sr at λ = 16, 0.098 sr at λ = 64).
float srbfIntegral(float bandwidth);

// cos α of the angle α beyond which G < 10⁻³, the paper's cut-off:
// 1 − ln(1000) / λ.
float srbfSupportCosine(float bandwidth);

}  // namespace hdhair
