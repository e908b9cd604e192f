#include "hdHair/environment/NonNegativeLeastSquares.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace hdhair {

namespace {

// Solves G_PP s = h_P for the free set P by Cholesky.
std::vector<double> solveFree(const std::vector<double>& gram, const std::vector<double>& projections,
                              const std::vector<size_t>& free, double ridge) {
    const size_t n = projections.size();
    const size_t m = free.size();
    std::vector<double> lower(m * m, 0.0);
    for (size_t i = 0; i < m; ++i) {
        for (size_t j = 0; j <= i; ++j) {
            double sum = gram[free[i] * n + free[j]] + (i == j ? ridge : 0.0);
            for (size_t k = 0; k < j; ++k) sum -= lower[i * m + k] * lower[j * m + k];
            if (i == j) {
                lower[i * m + i] = std::sqrt(std::max(sum, ridge));
            } else {
                lower[i * m + j] = sum / lower[j * m + j];
            }
        }
    }
    std::vector<double> s(m);
    for (size_t i = 0; i < m; ++i) {
        double sum = projections[free[i]];
        for (size_t k = 0; k < i; ++k) sum -= lower[i * m + k] * s[k];
        s[i] = sum / lower[i * m + i];
    }
    for (size_t i = m; i-- > 0;) {
        double sum = s[i];
        for (size_t k = i + 1; k < m; ++k) sum -= lower[k * m + i] * s[k];
        s[i] = sum / lower[i * m + i];
    }
    return s;
}

}  // namespace

std::vector<double> nonNegativeLeastSquares(const std::vector<double>& gram, const std::vector<double>& projections) {
    const size_t n = projections.size();
    if (gram.size() != n * n) throw std::invalid_argument("nonNegativeLeastSquares: the Gram matrix is not n × n");
    std::vector<double> x(n, 0.0);
    if (n == 0) return x;
    double trace = 0.0, scale = 0.0;
    for (size_t i = 0; i < n; ++i) {
        trace += gram[i * n + i];
        scale = std::max(scale, std::fabs(projections[i]));
    }
    const double ridge = 1e-10 * std::max(trace / double(n), 1e-300);
    const double tolerance = 1e-12 * std::max(scale, 1e-300);

    std::vector<bool> isFree(n, false);
    // Each round frees one variable; the inner loop only ever fixes
    // variables again, so 3n rounds is ample (Lawson and Hanson use 3n).
    for (size_t round = 0; round < 3 * n; ++round) {
        // The gradient of −½‖Ax − b‖²: h − G x; the most promising fixed variable.
        size_t best = n;
        double bestGradient = tolerance;
        for (size_t j = 0; j < n; ++j) {
            if (isFree[j]) continue;
            double gradient = projections[j];
            for (size_t k = 0; k < n; ++k) gradient -= gram[j * n + k] * x[k];
            if (gradient > bestGradient) {
                bestGradient = gradient;
                best = j;
            }
        }
        if (best == n) break;  // Kuhn-Tucker conditions hold
        isFree[best] = true;
        for (;;) {
            std::vector<size_t> free;
            for (size_t j = 0; j < n; ++j)
                if (isFree[j]) free.push_back(j);
            const std::vector<double> s = solveFree(gram, projections, free, ridge);
            // Step from x towards s as far as every free variable stays
            // non-negative; the ones that reach 0 are fixed again.
            double step = 1.0;
            size_t blocking = free.size();
            for (size_t i = 0; i < free.size(); ++i) {
                if (s[i] > 0.0) continue;
                const double reach = x[free[i]] / (x[free[i]] - s[i]);
                if (reach < step) {
                    step = reach;
                    blocking = i;
                }
            }
            for (size_t i = 0; i < free.size(); ++i) x[free[i]] += step * (s[i] - x[free[i]]);
            if (blocking == free.size()) break;
            x[free[blocking]] = 0.0;  // exactly, whatever rounding left
            for (size_t i = 0; i < free.size(); ++i) {
                if (x[free[i]] <= 0.0) {
                    x[free[i]] = 0.0;
                    isFree[free[i]] = false;
                }
            }
        }
    }
    return x;
}

}  // namespace hdhair
