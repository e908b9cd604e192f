#pragma once
// Exponentially scaled modified Bessel functions of the first kind,
// e^(−κ) I_n(κ) for n = 0 .. maxOrder: the Fourier coefficients of the von
// Mises kernel, e^(κ(cos Δ − 1)) = Σ_n e^(−κ) I_n(κ) e^(inΔ)
// (Abramowitz & Stegun 9.6.34). SrbfConvolutionTables.h convolves the
// Marschner azimuthal terms N_p with the azimuthal factor of an SRBF through
// them: each Fourier mode of N_p is multiplied by 2π e^(−κ) I_n(κ).
//
// Miller's backward recurrence (A&S 9.6.26, I_(n−1) = I_(n+1) + (2n/κ) I_n),
// started well above maxOrder and normalised with
// e^κ = I_0(κ) + 2 Σ_(n≥1) I_n(κ) (A&S 9.6.37 at Δ = 0), so no I_0 series or
// asymptotic expansion is needed and nothing overflows for any κ >= 0.

#include <vector>

namespace hdhair {

// out[n] = e^(−κ) I_n(κ) for n = 0 .. maxOrder (out is resized); every value
// is in [0, 1] and they are decreasing in n. κ < 0 or non-finite counts as 0.
void scaledModifiedBesselI(double kappa, int maxOrder, std::vector<double>& out);

}  // namespace hdhair
