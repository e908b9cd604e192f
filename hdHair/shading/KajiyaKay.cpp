#include "hdHair/shading/KajiyaKay.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>


namespace hdhair {
namespace {

glm::vec3 normalizedOrZero(const glm::vec3& v) {
    float length = glm::length(v);
    return (std::isfinite(length) && length > 1e-20f) ? v / length : glm::vec3(0.0f);
}

}  // namespace

KajiyaKayTerms evaluateKajiyaKay(const glm::vec3& t, const glm::vec3& l, const glm::vec3& e,
                                 const KajiyaKayParameters& parameters) {
    glm::vec3 tn = normalizedOrZero(t), ln = normalizedOrZero(l), en = normalizedOrZero(e);
    float tl = std::clamp(glm::dot(tn, ln), -1.0f, 1.0f);
    float te = std::clamp(glm::dot(tn, en), -1.0f, 1.0f);
    // max() before sqrt: rounding can make 1 - x^2 slightly negative.
    float sinTl = std::sqrt(std::max(0.0f, 1.0f - tl * tl));
    float sinTe = std::sqrt(std::max(0.0f, 1.0f - te * te));
    float cosToCone = std::clamp(sinTl * sinTe - tl * te, 0.0f, 1.0f);
    KajiyaKayTerms terms;
    constexpr float inversePi = 0.31830988618379067f;
    terms.diffuse = parameters.diffuse * inversePi * sinTl;
    terms.specular = parameters.specular * inversePi * std::pow(cosToCone, std::max(parameters.shininess, 1.0f));
    return terms;
}

}  // namespace hdhair
