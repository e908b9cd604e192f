#include "hdHair/environment/Srbf.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

namespace hdhair {

float srbfKernel(const glm::vec3& direction, const glm::vec3& centre, float bandwidth) {
    return std::exp(bandwidth * (glm::dot(direction, centre) - 1.0f));
}

glm::vec3 srbfRadiance(const std::vector<Srbf>& srbfs, const glm::vec3& direction) {
    glm::vec3 sum(0.0f);
    for (const Srbf& srbf : srbfs) sum += srbf.amplitude * srbfKernel(direction, srbf.centre, srbf.bandwidth);
    return sum;
}

float srbfIntegral(float bandwidth) {
    return glm::two_pi<float>() * -std::expm1(-2.0f * bandwidth) / bandwidth;
}

float srbfSupportCosine(float bandwidth) { return 1.0f - std::log(1000.0f) / bandwidth; }

}  // namespace hdhair
