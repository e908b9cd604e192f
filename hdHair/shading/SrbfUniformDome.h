#pragma once
// A fibre's response to a uniform dome (an untextured DomeLight, or one whose
// texture failed), from its SRBF-convolution table: per unit radiance,
//   U(θ_o) = ∫ f(ωi, ωo) dωi  over the sphere,
// f as in SrbfConvolution.h (Marschner S cos θ_i; Kajiya-Kay's diffuse and
// specular terms for Kd = Ks = 1). Exactly, without fitting the dome: the
// kernel integrates to the same ∫G dω about every centre, so
//   ∫ I(ωo; ξ, λ) dξ = ∫ f(ωi) ∫ G(ωi; ξ, λ) dξ dωi = (∫G dω) · U(θ_o),
// and U is the table's λ = 16 slab (the smoothest in ξ) integrated over
// every centre ξ: cos θ_ξ dθ_ξ, and ψ over [0, π] twice (I is even in ψ),
// by the trapezoid rule on the table's nodes. One value per θ_o node, what
// the shader interpolates. Kajiya-Kay's diffuse part is Kd·π exactly
// (∫ sin(t, ω)/π dω = π); the test checks the table gives it.

#include <vector>

#include <glm/vec3.hpp>

#include "hdHair/shading/SrbfConvolutionTables.h"

namespace hdhair {

// One value per θ_o node of `table` (its height): RGB for the Marschner
// kinds, (diffuse, specular, 0) for Kajiya-Kay.
std::vector<glm::vec3> srbfUniformDomeResponse(const SrbfConvolutionTable& table);

// The response at θ_o, interpolated linearly between nodes as the shader does.
glm::vec3 sampleSrbfUniformDome(const std::vector<glm::vec3>& response, float thetaO);

}  // namespace hdhair
