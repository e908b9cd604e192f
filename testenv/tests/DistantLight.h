#pragma once
// A distant light for scenes built in code, shining from a given direction:
// UsdLux lights emit along their -Z, so +Z is turned to `towardsLight`.

#include <cmath>
#include <string>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include "hdHair/scene/LightPrim.h"

namespace hdhair::testenv {

inline LightPrim distantLightFrom(glm::dvec3 towardsLight, const std::string& path = "/light",
                                  float intensity = 2.0f) {
    LightPrim light;
    light.path = path;
    light.intensity = intensity;
    glm::dvec3 z = glm::normalize(towardsLight);
    glm::dvec3 x = glm::normalize(glm::cross(std::abs(z.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0), z));
    glm::dvec3 y = glm::cross(z, x);
    light.worldTransform = glm::dmat4(glm::dvec4(x, 0), glm::dvec4(y, 0), glm::dvec4(z, 0), glm::dvec4(0, 0, 0, 1));
    return light;
}

}  // namespace hdhair::testenv
