// A uniform dome's response from the SRBF tables (SrbfUniformDome.h) against
// the CPU models integrated over the sphere directly.

#include <cmath>

#include <gtest/gtest.h>

#include "hdHair/shading/KajiyaKay.h"
#include "hdHair/shading/Marschner.h"
#include "hdHair/shading/SrbfUniformDome.h"

using namespace hdhair;

namespace {

constexpr double kPi = 3.141592653589793;

// t = +x; θ from the normal plane, φ in the yz plane.
glm::vec3 direction(double theta, double phi) {
    return glm::vec3(float(std::sin(theta)), float(std::cos(theta) * std::cos(phi)),
                     float(std::cos(theta) * std::sin(phi)));
}

// ∫ f(ωi) dωi over the sphere by the midpoint rule, dω = cos θ dθ dφ.
template <typename Response>
glm::dvec3 integrateOverSphere(const Response& response, int thetaSteps, int phiSteps) {
    glm::dvec3 sum(0.0);
    const double dTheta = kPi / thetaSteps, dPhi = 2.0 * kPi / phiSteps;
    for (int i = 0; i < thetaSteps; ++i) {
        const double theta = -0.5 * kPi + (i + 0.5) * dTheta;
        for (int j = 0; j < phiSteps; ++j)
            sum += glm::dvec3(response(direction(theta, (j + 0.5) * dPhi))) * std::cos(theta) * dTheta * dPhi;
    }
    return sum;
}

}  // namespace

TEST(SrbfUniformDome, KajiyaKayDiffuseIsPiAndSpecularMatchesTheModel) {
    // ∫ Kd/π sin(t, ω) dω = Kd π; the specular part has no closed form.
    const KajiyaKayParameters unit{1.0f, 1.0f, 60.0f};
    const SrbfConvolutionTable table = buildSrbfKajiyaKayTable(unit.shininess);
    const std::vector<glm::vec3> response = srbfUniformDomeResponse(table);
    ASSERT_EQ(response.size(), size_t(table.height()));
    const glm::vec3 t(1.0f, 0.0f, 0.0f);
    for (double thetaO : {-1.2, -0.4, 0.0, 0.3, 1.0}) {
        const glm::vec3 wo = direction(thetaO, 0.7);
        const glm::dvec3 expected = integrateOverSphere(
            [&](const glm::vec3& wi) {
                KajiyaKayTerms terms = evaluateKajiyaKay(t, wi, wo, unit);
                return glm::vec3(terms.diffuse, terms.specular, 0.0f);
            },
            720, 90);
        EXPECT_NEAR(expected.x, kPi, 1e-3 * kPi);  // the model itself: Kd π
        const glm::vec3 fromTable = sampleSrbfUniformDome(response, float(thetaO));
        EXPECT_NEAR(fromTable.x, kPi, 0.01 * kPi) << thetaO;
        EXPECT_NEAR(fromTable.y, expected.y, 0.02 * expected.y + 1e-4) << thetaO;
    }
}

TEST(SrbfUniformDome, MarschnerMatchesTheModelIntegratedOverTheSphere) {
    MarschnerParameters brown;
    const SrbfConvolutionTable table = buildSrbfMarschnerTable(brown);
    const std::vector<glm::vec3> response = srbfUniformDomeResponse(table);
    const glm::vec3 t(1.0f, 0.0f, 0.0f);
    for (double thetaO : {-0.9, 0.0, 0.5}) {
        const glm::vec3 wo = direction(thetaO, 0.3);
        const glm::dvec3 expected = integrateOverSphere(
            [&](const glm::vec3& wi) { return evaluateMarschner(t, wi, wo, brown).radiance(); }, 360, 180);
        const glm::vec3 fromTable = sampleSrbfUniformDome(response, float(thetaO));
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(fromTable[c], expected[c], 0.02 * expected[c] + 1e-4) << thetaO;
    }
}

TEST(SrbfUniformDome, AScaledTableFailsTheComparison) {
    // The comparison above is sharp enough to see a 5 % error in the table.
    const KajiyaKayParameters unit{1.0f, 1.0f, 60.0f};
    SrbfConvolutionTable table = buildSrbfKajiyaKayTable(unit.shininess);
    for (float& value : table.texels) value *= 1.05f;
    const glm::vec3 fromTable = sampleSrbfUniformDome(srbfUniformDomeResponse(table), 0.0f);
    EXPECT_GT(std::abs(fromTable.x - kPi), 0.01 * kPi);
}
