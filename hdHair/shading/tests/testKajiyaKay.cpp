// Kajiya-Kay must stay finite and within [0, Kd] and [0, Ks] for every
// geometry, including the degenerate ones hair produces all the time.

#include <cmath>
#include <random>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "hdHair/shading/KajiyaKay.h"

using namespace hdhair;

namespace {

constexpr float kInversePi = 0.31830988618379067f;

void expectBounded(const KajiyaKayTerms& terms, const KajiyaKayParameters& p) {
    EXPECT_TRUE(std::isfinite(terms.diffuse));
    EXPECT_TRUE(std::isfinite(terms.specular));
    EXPECT_GE(terms.diffuse, 0.0f);
    EXPECT_LE(terms.diffuse, p.diffuse * kInversePi * (1.0f + 1e-6f));
    EXPECT_GE(terms.specular, 0.0f);
    EXPECT_LE(terms.specular, p.specular * kInversePi * (1.0f + 1e-6f));
}

}  // namespace

TEST(KajiyaKay, DiffuseIsSineOfTangentToLight) {
    KajiyaKayParameters p;
    glm::vec3 t(1, 0, 0), e(0, 0, 1);
    EXPECT_NEAR(evaluateKajiyaKay(t, {0, 1, 0}, e, p).diffuse, p.diffuse * kInversePi, 1e-6f);
    EXPECT_NEAR(evaluateKajiyaKay(t, {1, 0, 0}, e, p).diffuse, 0.0f, 1e-6f);
    EXPECT_NEAR(evaluateKajiyaKay(t, glm::normalize(glm::vec3(1, 1, 0)), e, p).diffuse,
                p.diffuse * kInversePi * std::sqrt(0.5f), 1e-6f);
}

TEST(KajiyaKay, SpecularPeaksOnTheMirrorCone) {
    KajiyaKayParameters p;
    glm::vec3 t(1, 0, 0);
    // Light at 60 degrees to the tangent; the mirror cone is at 120 degrees.
    glm::vec3 l(std::cos(1.0472f), std::sin(1.0472f), 0.0f);
    glm::vec3 onCone(std::cos(2.0944f), 0.0f, std::sin(2.0944f));     // any azimuth on the cone
    glm::vec3 offCone(std::cos(1.0472f), 0.0f, std::sin(1.0472f));    // same side as the light
    EXPECT_NEAR(evaluateKajiyaKay(t, l, onCone, p).specular, p.specular * kInversePi, 1e-4f);
    EXPECT_LT(evaluateKajiyaKay(t, l, offCone, p).specular, 0.01f * p.specular * kInversePi);
}

TEST(KajiyaKay, TangentParallelToLightOrEye) {
    KajiyaKayParameters p;
    glm::vec3 t(0, 1, 0);
    KajiyaKayTerms toLight = evaluateKajiyaKay(t, t, {0, 0, 1}, p);
    expectBounded(toLight, p);
    EXPECT_NEAR(toLight.diffuse, 0.0f, 1e-6f);
    expectBounded(evaluateKajiyaKay(t, {0, 0, 1}, t, p), p);
    expectBounded(evaluateKajiyaKay(t, t, t, p), p);
    expectBounded(evaluateKajiyaKay(t, -t, t, p), p);  // light exactly behind, along the fibre
}

TEST(KajiyaKay, ZeroLengthAndExtremeVectors) {
    KajiyaKayParameters p;
    glm::vec3 zero(0.0f);
    expectBounded(evaluateKajiyaKay(zero, {0, 1, 0}, {0, 0, 1}, p), p);
    expectBounded(evaluateKajiyaKay({1, 0, 0}, zero, zero, p), p);
    expectBounded(evaluateKajiyaKay({1e-30f, 0, 0}, {0, 1e30f, 0}, {0, 0, 1e-20f}, p), p);
    expectBounded(evaluateKajiyaKay({1e30f, 1e30f, 0}, {0, 1, 0}, {0, 0, 1}, p), p);
}

TEST(KajiyaKay, GrazingAnglesAndRandomDirectionsStayBounded) {
    KajiyaKayParameters p;
    p.shininess = 500.0f;
    std::mt19937 random(7);
    std::normal_distribution<float> gaussian;
    for (int i = 0; i < 20000; ++i) {
        glm::vec3 t(gaussian(random), gaussian(random), gaussian(random));
        glm::vec3 l(gaussian(random), gaussian(random), gaussian(random));
        // Every fourth sample puts the eye almost exactly on the tangent.
        glm::vec3 e = (i % 4 == 0) ? t + 1e-7f * l : glm::vec3(gaussian(random), gaussian(random), gaussian(random));
        expectBounded(evaluateKajiyaKay(t, l, e, p), p);
    }
}
