#pragma once
// Non-negative least squares on the normal equations: the x ≥ 0 minimising
// ‖A x − b‖², given only G = AᵀA (n × n, symmetric positive semi-definite)
// and h = Aᵀb. The SRBF fit re-solves its amplitudes this way after every
// insertion: n is the number of lobes (tens), while A would have a row per
// grid cell (thousands), so G and h are what it keeps.
//
// The active-set method of Lawson and Hanson ("Solving Least Squares
// Problems", 1974, ch. 23, algorithm NNLS), with each unconstrained
// sub-problem solved by Cholesky on the free variables' block of G (its
// diagonal raised by 1e-10 of its mean, so that two nearly identical lobes
// do not make it singular). Deterministic: ties go to the lowest index and
// no step depends on anything but G and h.

#include <vector>

namespace hdhair {

// `gram` is n × n, row-major. Returns x (n values, each ≥ 0).
std::vector<double> nonNegativeLeastSquares(const std::vector<double>& gram, const std::vector<double>& projections);

}  // namespace hdhair
