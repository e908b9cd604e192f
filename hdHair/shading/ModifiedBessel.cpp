#include "hdHair/shading/ModifiedBessel.h"

#include <algorithm>
#include <cmath>

namespace hdhair {

void scaledModifiedBesselI(double kappa, int maxOrder, std::vector<double>& out) {
    const int orders = std::max(0, maxOrder);
    out.assign(std::size_t(orders) + 1, 0.0);
    const double k = std::isfinite(kappa) ? std::max(0.0, kappa) : 0.0;
    if (k < 1e-12) {
        // I_0 = 1 + O(κ²), I_1 = κ/2 + O(κ³), the rest O(κ²) and below.
        out[0] = 1.0 - k;
        if (orders >= 1) out[1] = 0.5 * k;
        return;
    }
    // I_n/I_0 ≈ exp(−n²/(2κ)) for n ≲ κ: below 1e-17 from n = √(80κ) on, so
    // the terms the sum leaves out above `start` are negligible.
    const int start = std::max(orders, int(std::ceil(std::sqrt(80.0 * k)))) + 24;
    double above = 0.0, current = 1e-280, sum = 0.0;
    for (int n = start; n >= 1; --n) {
        if (n <= orders) out[std::size_t(n)] = current;
        sum += 2.0 * current;
        double below = above + (2.0 * n / k) * current;
        above = current;
        current = below;
        if (current > 1e250) {  // rescale everything computed so far
            above *= 1e-250;
            current *= 1e-250;
            sum *= 1e-250;
            for (int m = n; m <= orders; ++m) out[std::size_t(m)] *= 1e-250;
        }
    }
    out[0] = current;
    sum += current;
    for (double& value : out) value = std::clamp(value / sum, 0.0, 1.0);
}

}  // namespace hdhair
