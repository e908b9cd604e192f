#include "hdHair/environment/RadianceGridBlur.h"

#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>

namespace hdhair {

RadianceGrid blurredGrid(const RadianceGrid& grid, float bandwidth) {
    if (!(bandwidth > 0.0f)) throw std::invalid_argument("blurredGrid: the bandwidth must be positive");
    // G ≥ 10⁻⁶ where λ (cos θ − 1) ≥ ln 10⁻⁶.
    const float cutoff = 1.0f + std::log(1e-6f) / bandwidth;
    RadianceGrid blurred = grid;
    for (size_t s = 0; s < grid.cellCount(); ++s) {
        glm::dvec3 sum(0.0);
        double weight = 0.0;
        for (size_t t = 0; t < grid.cellCount(); ++t) {
            const float cosine = glm::dot(grid.directions[s], grid.directions[t]);
            if (cosine < cutoff) continue;
            const double w = grid.solidAngles[t] * std::exp(bandwidth * (cosine - 1.0f));
            sum += w * glm::dvec3(grid.radiance[t]);
            weight += w;
        }
        blurred.radiance[s] = glm::vec3(sum / weight);
    }
    return blurred;
}

}  // namespace hdhair
