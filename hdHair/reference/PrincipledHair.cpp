#include "hdHair/reference/PrincipledHair.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>

namespace hdhair {

float principledHairRoughness(float betaR) {
    // √v(β_m) = 0.726β_m + 0.812β_m² + 3.7β_m²⁰ rises monotonically on [0, 1]
    // (from 0 to 5.238): bisection finds the root to float precision.
    const double target = std::clamp(2.0 * double(std::abs(betaR)), 0.0, 5.238);
    if (target <= 0.0) return 0.0f;
    double lo = 0.0, hi = 1.0;
    for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (lo + hi);
        const double root = 0.726 * mid + 0.812 * mid * mid + 3.7 * std::pow(mid, 20.0);
        (root < target ? lo : hi) = mid;
    }
    return float(0.5 * (lo + hi));
}

PrincipledHair principledHairFrom(const MarschnerParameters& marschner) {
    PrincipledHair hair;
    hair.absorption = glm::max(marschner.sigmaA, glm::vec3(0.0f));
    hair.roughness = principledHairRoughness(marschner.beta.x);
    hair.ior = std::max(marschner.eta, 1.0f);
    hair.offset = -marschner.alpha.x;
    return hair;
}

}  // namespace hdhair
