#pragma once
// The yardstick the SRBF dome lighting is measured against: the
// dome integrated with many distant lights, importance sampled from its
// radiance, each of which can cast its own deep-opacity shadow like any
// other distant light. Ren et al. 2010 (§8, Fig. 6 and 8) make their
// references the same way, with 6,144 directional lights; minutes a frame is
// fine for a reference.
//
// Monte Carlo form: the radiance a fibre scatters towards the eye,
//   L_o = ∫ L(ω) T(ω) S(ω, ωo) cos θ_i dω  (Ren eq. 1),
// is estimated with N directions ω_k drawn with density p(ω) as
//   L_o ≈ (1/N) Σ_k L(ω_k) T(ω_k) S(ω_k, ωo) cos θ_k / p(ω_k),
// which is exactly what N distant lights of irradiance (at normal incidence)
//   E_k = L(ω_k) / (N p(ω_k))
// from the directions ω_k give through the ordinary light path.
//
// Sampling: the map is the piecewise-constant radiance of a latlong grid
// (RadianceGrid.h, in the dome's frame). A cell c is picked with probability
// P_c = Y_c Ω_c / W (Y the Rec. 709 luminance of its radiance, Ω_c its solid
// angle, W = Σ Y_c Ω_c), and a direction uniformly in its solid angle, so
// p(ω) = Y_c / W and E_k = L_c W / (N Y_c): every light carries the same
// luminous share W / N of the dome, coloured by its cell. The N cells are
// picked by systematic sampling of the cumulative weights at (k + ½)/N, and
// the position within the cell by the radical inverses of k in bases 2 and 3
// (Hammersley-style), so the lights are stratified, deterministic and the
// same from run to run; brighter cells get proportionally more lights.
// An untextured dome is the grid of its uniform radiance (uniformDomeGrid),
// sampled the same way: directions spread over the sphere by solid angle.

#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "hdHair/environment/RadianceGrid.h"

namespace hdhair {

// More lights than this is a request error (std::invalid_argument): each
// light is a shadow map and a shading term.
constexpr int kMaxSampledDomeLights = 65536;

struct SampledDomeLight {
    glm::vec3 direction{0.0f, 1.0f, 0.0f};  // world space, unit, towards the dome
    glm::vec3 irradiance{0.0f};             // E_k at normal incidence, linear RGB
};

// `count` distant lights (1..kMaxSampledDomeLights) for the radiance on
// `grid` (the dome's frame), turned into world space by the dome's
// transform (LatlongDirections.h: domeLightDirectionToWorld). A grid with no
// light (every cell black) gives none.
std::vector<SampledDomeLight> sampleDomeLights(const RadianceGrid& grid, const glm::dmat4& domeToWorld, int count);

// A width × height latlong grid of the uniform `radiance`.
RadianceGrid uniformDomeGrid(const glm::vec3& radiance, int width, int height);

}  // namespace hdhair
