#pragma once
// One Gaussian spherical radial basis function (SRBF) of a dome light's fit
// (issue 16; Ren, Zhou, Li, Hua & Guo 2010, "Interactive Hair Rendering under
// Environment Lighting", §2 eq. (2), after Tsai & Shih 2006):
//   G(ω; ξ, λ) = exp(λ (ω·ξ − 1))
// centre ξ (a unit direction: the lobe's radiance comes *from* ξ, like ωi),
// bandwidth λ. The peak G(ξ) is 1, so a lobe's amplitude L_j is a peak
// radiance, not a power; ∫ G dω = 2π (1 − e^(−2λ))/λ (0.3927 sr at λ = 16,
// 0.0982 sr at λ = 64). For large λ, G ≈ exp(−λ θ²/2): an angular standard
// deviation of 1/√λ (14.3° at λ = 16, 7.2° at λ = 64). The fit bounds λ to
// [16, 64] (Ren §7): wider lobes break the transmittance approximation,
// narrower ones need too many lobes. No cut-off is applied here (the paper's
// 10⁻³ support is for shadow filtering only).

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace hdhair {

constexpr float kSrbfMinBandwidth = 16.0f;
constexpr float kSrbfMaxBandwidth = 64.0f;

struct SrbfLobe {
    glm::vec3 axis{0.0f, 0.0f, 1.0f};  // ξ, unit length
    float bandwidth = kSrbfMinBandwidth;  // λ > 0
};

// G(ω; ξ, λ) for a unit ω.
inline double srbfValue(const SrbfLobe& lobe, const glm::dvec3& direction) {
    return std::exp(double(lobe.bandwidth) * (glm::dot(direction, glm::dvec3(lobe.axis)) - 1.0));
}

// ∫ G(ω; ξ, λ) dω over the sphere: the irradiance (normal to ξ) of the
// distant light a lobe becomes as λ → ∞.
inline double srbfSolidAngle(double bandwidth) {
    constexpr double twoPi = 6.283185307179586;
    return twoPi * -std::expm1(-2.0 * bandwidth) / bandwidth;
}

}  // namespace hdhair
