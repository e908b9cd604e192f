#include "hdHair/environment/Srbf.h"

namespace hdhair {

glm::vec3 srbfRadiance(const std::vector<Srbf>& srbfs, const glm::vec3& direction) {
    glm::vec3 sum(0.0f);
    for (const Srbf& srbf : srbfs)
        sum += srbf.amplitude * srbfKernel(direction, srbf.lobe.centre, srbf.lobe.bandwidth);
    return sum;
}

float srbfSupportCosine(float bandwidth) { return 1.0f - std::log(1000.0f) / bandwidth; }

}  // namespace hdhair
