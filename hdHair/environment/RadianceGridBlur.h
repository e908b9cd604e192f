#pragma once
// Blurs an environment grid with a normalised Gaussian SRBF: the prefilter
// the SRBF fit applies before fitting (SrbfFit.h), and why.
//
// A lobe can be no narrower than λ = 64 (Ren et al. 2010, §7). A least-
// squares fit of a source narrower than that, a sun, gives the lobe the
// amplitude Φ / ∫G² and so the power Φ ∫G / ∫G² = 2Φ: twice the light
// (for a point source; a little less for a 5° disc). Blurring the map first
// with the narrowest lobe's own shape, normalised, makes a point source
// exactly a λ = 64 lobe of the same power, and changes wide features little
// (a λ = 16 lobe blurred by λ = 64 is close to λ = 12.8): the fit then sees
// only what SRBFs can show.
//
// Each cell becomes Σ_t ω_t G(d_s · d_t) L_t / Σ_t ω_t G(d_s · d_t), over
// the cells t where G ≥ 10⁻⁶ (the rest weigh less than a millionth): a
// uniform map stays exactly uniform, and the map's power is kept to the
// grid's discretisation.

#include "hdHair/environment/RadianceGrid.h"

namespace hdhair {

// `grid` blurred with G(·; ·, bandwidth), bandwidth > 0.
RadianceGrid blurredGrid(const RadianceGrid& grid, float bandwidth);

}  // namespace hdhair
