#include "hdHair/shading/SrbfVaryingAbsorption.h"

#include <algorithm>
#include <cmath>

namespace hdhair {

SrbfLobeAttenuation srbfLobeAttenuation(const glm::vec3& sigmaA, float cosThetaO,
                                        const MarschnerParameters& parameters) {
    MarschnerParameters absorbing = parameters, clear = parameters;
    absorbing.sigmaA = sigmaA;
    clear.sigmaA = glm::vec3(0.0f);
    glm::vec3 sums[2][2] = {{glm::vec3(0.0f), glm::vec3(0.0f)}, {glm::vec3(0.0f), glm::vec3(0.0f)}};
    for (int i = 0; i < kSrbfAttenuationNodes; ++i) {
        float h = (float(i) + 0.5f) / float(kSrbfAttenuationNodes);
        for (int lobe = 0; lobe < 2; ++lobe) {
            sums[lobe][0] += marschnerAttenuation(lobe + 1, h, cosThetaO, absorbing);
            sums[lobe][1] += marschnerAttenuation(lobe + 1, h, cosThetaO, clear);
        }
    }
    // Where the lobe carries no energy at all (cos θ_o = 0: Fresnel reflects
    // everything), 1: there is nothing to attenuate.
    auto ratio = [](const glm::vec3& absorbed, const glm::vec3& white) {
        glm::vec3 r;
        for (int c = 0; c < 3; ++c) r[c] = white[c] > 0.0f ? std::clamp(absorbed[c] / white[c], 0.0f, 1.0f) : 1.0f;
        return r;
    };
    SrbfLobeAttenuation attenuation;
    attenuation.TT = ratio(sums[0][0], sums[0][1]);
    attenuation.TRT = ratio(sums[1][0], sums[1][1]);
    return attenuation;
}

glm::vec3 evaluateSrbfMarschnerVaryingAbsorption(const SrbfConvolutionTable& lobeTable, const glm::vec3& t,
                                                 const glm::vec3& wo, const SrbfLobe& lobe,
                                                 const glm::vec3& sigmaA, const MarschnerParameters& parameters) {
    SrbfTableAngles angles = srbfTableAngles(t, wo, lobe);
    glm::vec3 lobes = sampleSrbfTable(lobeTable, angles);  // (R, TT, TRT)
    SrbfLobeAttenuation attenuation = srbfLobeAttenuation(sigmaA, std::cos(angles.thetaO), parameters);
    return glm::vec3(lobes.x) + attenuation.TT * lobes.y + attenuation.TRT * lobes.z;
}

}  // namespace hdhair
