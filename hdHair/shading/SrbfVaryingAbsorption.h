#pragma once
// The SRBF-convolution fallback for Marschner prims whose absorption σ_a
// varies per curve or per vertex (HairMaterial's kAbsorptionVaries), where no
// per-material RGB table (SrbfConvolutionTables.h, MarschnerColour) fits.
//
// Choice: one table per (η, α_p, β_p, caustic) with the three lobes apart at
// σ_a = 0 (MarschnerLobes: R, TT, TRT), and the absorption put back per
// fragment as each lobe's energy ratio at the fragment's θ_o:
//   L ≈ R + T̄_TT · TT + T̄_TRT · TRT,
//   T̄_p(σ_a, θ_o) = ∫_0^1 A(p, h; σ_a) dh / ∫_0^1 A(p, h; 0) dh,
// A the attenuation of Marschner eqs. (6), (9) with N_p's setup at θ_o
// (Marschner.h). Since ∫ N_p dφ = ½ ∫ A(p, h) dh (eq. 8's change of
// variables), T̄_p is exact for each lobe's total energy under a white
// azimuthally uniform light; what it misses is that absorption darkens the
// offsets h (and so the azimuths) of a lobe unevenly — TT's centre, the
// longest chord, most. The integral is a 16-node midpoint rule in h; it does
// not depend on the lobe, so the shader computes it once per fragment and
// applies it to every SRBF lobe. The table does not depend on σ_a, so every
// varying prim with the same η, α and β shares one.
// Rejected: the table of the prim's mean absorption (what the tabled
// directional path does): a blonde-to-black prim then has one colour.
// Measured error (README "SRBF-convolution tables"): the fallback against the
// exact RGB table of the fragment's own σ_a.

#include <glm/vec3.hpp>

#include "hdHair/shading/Marschner.h"
#include "hdHair/shading/SrbfConvolutionTables.h"

namespace hdhair {

constexpr int kSrbfAttenuationNodes = 16;

struct SrbfLobeAttenuation {
    glm::vec3 TT{1.0f}, TRT{1.0f};  // T̄_TT, T̄_TRT per channel, in [0, 1]
};

SrbfLobeAttenuation srbfLobeAttenuation(const glm::vec3& sigmaA, float cosThetaO,
                                        const MarschnerParameters& parameters);

// R + T̄_TT·TT + T̄_TRT·TRT from a MarschnerLobes table and the fragment's σ_a
// (parameters.sigmaA is not used; η and the caustic parameters must be the
// table's).
glm::vec3 evaluateSrbfMarschnerVaryingAbsorption(const SrbfConvolutionTable& lobeTable, const glm::vec3& t,
                                                 const glm::vec3& wo, const SrbfLobe& lobe,
                                                 const glm::vec3& sigmaA, const MarschnerParameters& parameters);

}  // namespace hdhair
