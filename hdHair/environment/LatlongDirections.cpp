#include "hdHair/environment/LatlongDirections.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

namespace hdhair {

glm::vec3 latlongDirection(float u, float v) {
    const float longitude = glm::pi<float>() * (1.0f - 2.0f * u);
    const float polar = glm::pi<float>() * v;
    const float sinPolar = std::sin(polar);
    return glm::vec3(sinPolar * std::sin(longitude), std::cos(polar), sinPolar * std::cos(longitude));
}

glm::vec2 latlongCoordinates(const glm::vec3& direction) {
    const glm::vec3 d = glm::normalize(direction);
    float u = 0.5f - std::atan2(d.x, d.z) / glm::two_pi<float>();
    if (u >= 1.0f) u -= 1.0f;  // atan2 = −π (−Z, approached from −X) is u = 0, not 1
    const float v = std::acos(glm::clamp(d.y, -1.0f, 1.0f)) / glm::pi<float>();
    return glm::vec2(u, v);
}

glm::vec3 domeLightDirectionToWorld(const glm::dmat4& domeToWorld, const glm::vec3& domeDirection) {
    return glm::vec3(glm::normalize(glm::dmat3(domeToWorld) * glm::dvec3(domeDirection)));
}

glm::vec3 worldDirectionToDomeLight(const glm::dmat4& domeToWorld, const glm::vec3& worldDirection) {
    return glm::vec3(glm::normalize(glm::inverse(glm::dmat3(domeToWorld)) * glm::dvec3(worldDirection)));
}

}  // namespace hdhair
