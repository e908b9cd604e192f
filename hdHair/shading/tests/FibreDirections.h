#pragma once
// Directions about a fibre along +X, as the shading tests build them, and
// the check every shading value must pass.

#include <cmath>

#include <glm/vec3.hpp>

namespace hdhair::test {

// θ from the normal plane, φ in the yz plane; the tangent is +X.
inline glm::vec3 fibreDirection(float theta, float phi) {
    return glm::vec3(std::sin(theta), std::cos(theta) * std::cos(phi), std::cos(theta) * std::sin(phi));
}

inline bool finiteNonNegative(const glm::vec3& v) {
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(v[i]) || v[i] < 0.0f) return false;
    return true;
}

}  // namespace hdhair::test
