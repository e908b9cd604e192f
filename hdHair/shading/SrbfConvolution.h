#pragma once
// The radiance a fibre scatters towards ωo when lit by one SRBF lobe of unit
// amplitude (hdHair/environment/Srbf.h), integrated numerically: the CPU reference that the
// precomputed tables (SrbfConvolutionTables.h) are built against and tested
// against. Slow (a million integrand evaluations); never called per frame.
//
// Ren, Zhou, Li, Hua & Guo 2010, eq. (4) without the transmittance T̃ and with
// the fibre diameter D folded into the light's units, as in Marschner.h:
//   L_o(ωo; ξ, λ) = ∫ G(ωi; ξ, λ) S(ωi, ωo) cos θ_i dωi = ∫ G(ωi; ξ, λ) f(ωi, ωo) dωi,
// f = S cos θ_i being the radiance towards ωo per unit irradiance from ωi:
//   Marschner:  f = Σ_p M_p N_p (MarschnerLobes, Marschner 2003 eqs. (1)–(2)
//               with d'Eon 2011's M_p);
//   Kajiya-Kay: f = Kd/π sin(t, ωi) · colour + Ks/π cos^p(θ_e − θ_r)
//               (KajiyaKayTerms, the response to a distant light of irradiance 1).
// So a distant light of irradiance E from ξ gives E·f(ξ, ωo), and as λ → ∞
// L_o → f(ξ, ωo) · ∫ G dω = f(ξ, ωo) · srbfIntegral(λ): a sharp lobe is a
// distant light of irradiance ∫ G dω (tested).
//
// Quadrature: the product midpoint rule on the fibre-frame angles
// (θ_i ∈ [−π/2, π/2], dωi = cos θ_i dθ_i dφ_i; φ_i ∈ [−π, π) measured from
// ωo's azimuth), by default 720 × 1440 nodes (0.25° steps). G is evaluated
// as exp(λ(ωi·ξ − 1)) from the 3D vectors, independently of the tables'
// Fourier–Bessel factorisation. The narrowest features it must resolve are
// G at λ = 64 (σ = 7.2°) and the TT lobe's M (σ = 2β_TT = 7.5° at the
// defaults), so a step of 0.25° is far inside the midpoint rule's spectral
// range for Gaussians; halving the step changes the result by < 1e-5 of the
// peak (test ReferenceQuadratureIsConverged).
// t and wo must be non-zero; for wo along t the azimuth is measured from an
// arbitrary direction in the normal plane.

#include <glm/vec3.hpp>

#include "hdHair/shading/KajiyaKay.h"
#include "hdHair/shading/Marschner.h"
#include "hdHair/environment/Srbf.h"

namespace hdhair {

struct SrbfQuadrature {
    int inclinations = 720;  // θ_i nodes over [−π/2, π/2]
    int azimuths = 1440;     // φ_i nodes over [−π, π)
};

// L_o per Marschner lobe (R is colourless, TT and TRT carry the absorption).
struct SrbfMarschnerResponse {
    glm::vec3 R{0.0f}, TT{0.0f}, TRT{0.0f};
    glm::vec3 radiance() const { return R + TT + TRT; }
};

SrbfMarschnerResponse convolveSrbfMarschner(const glm::vec3& t, const glm::vec3& wo, const SrbfLobe& lobe,
                                            const MarschnerParameters& parameters,
                                            const SrbfQuadrature& quadrature = {});

// The Kajiya-Kay terms integrated against G: diffuse (multiply by the hair
// colour) and specular, Kd and Ks included, as evaluateKajiyaKay returns them.
KajiyaKayTerms convolveSrbfKajiyaKay(const glm::vec3& t, const glm::vec3& wo, const SrbfLobe& lobe,
                                     const KajiyaKayParameters& parameters, const SrbfQuadrature& quadrature = {});

}  // namespace hdhair
