#pragma once
// Where a deep opacity map's layers lie behind the nearest hair, and how
// their accumulated opacity becomes transmittance (Yuksel & Keyser 2008, as
// Svoboda 2012 section 1.5.4 implemented them; digest section 5.4).
//
// A light view's depth pass records z0, the nearest hair per texel. Layer k
// (k = 1..K, K = shadowLayers) ends at z0 + d_k, 0 < d_1 < ... < d_K, and
// stores the summed alpha of every fragment nearer than that, so the layers
// are cumulative; fragments beyond d_K are added to the last layer (the
// thesis's option (b): deep hair is not expected to be strongly lit), so
// layer K holds all the hair along the texel. d_K is shadowLayerDepth times
// the casters' depth range in the light's view.
//
// Spacing (shadowLayerSpacing):
//   linear  (default) the gap between layers grows linearly, d_k - d_{k-1}
//           proportional to k, so d_k = d_K k(k+1) / (K(K+1)): finest near
//           the lit surface, where transmittance changes fastest (Yuksel &
//           Keyser's recommendation, which the thesis confirms);
//   uniform d_k = d_K k / K.
//
// Lookup at linear depth z: d = z - z0 - b, where b is one texel's world size
// at that depth (a strand must not shadow itself where the camera's
// tessellation and the light's rasterisation disagree by less than a texel);
// d <= 0 is in front of all hair (opacity 0); between d_{k-1} and d_k
// (d_0 = 0, O_0 = 0) the opacity is interpolated linearly, as Kim & Neumann's
// opacity maps do between slices (thesis section 1.5.3); beyond d_K it is O_K.
//
// Transmittance (Kim & Neumann 2001, thesis section 1.5.3, tau = exp(-Omega),
// with the thesis's printed exp(+Omega) corrected, digest section 5.4):
//   T = exp(-k * Omega),  k = kShadowExtinction = 1,
// where Omega sums alpha = coverage x opacity, the very alpha the camera
// pass composites with. k = 1 because a fibre of alpha a passes 1 - a of the
// light behind it, and exp(-a) = 1 - a + O(a^2): for the thin, faint fibres
// hair is made of (coverage alpha of sub-texel strands is small), the
// product of (1 - a_i) over a texel's fibres is exp(-sum a_i) to first
// order, and for a uniform slab of fibres it is the Beer-Lambert law with
// the fibres' projected area per unit area as optical depth. Any other k
// would make a slab of known opacity darker or lighter than compositing the
// same fibres over each other. For nearly opaque fibres exp(-a) > 1 - a
// (exp(-1) = 0.37 where one opaque fibre passes nothing): such hair shadows
// less than the product would say.

#include <vector>

#include "hdHair/plan/SettingTokens.h"

namespace hdhair {

constexpr float kShadowExtinction = 1.0f;  // k in T = exp(-k * opacity)
constexpr int kMaxShadowLayers = 32;       // 8 RGBA16F targets: GL 4.5 guarantees 8 draw buffers

// d_k / d_K for k = 1..layers (the last is 1), increasing.
std::vector<float> deepOpacityLayerBoundaries(int layers, ShadowLayerSpacing spacing);

}  // namespace hdhair
