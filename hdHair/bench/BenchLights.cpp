#include "hdHair/bench/BenchLights.h"

#include <vector>

#include <glm/gtc/matrix_transform.hpp>

namespace hdhair {

void turnLightsAboutY(Scene& scene, double radians) {
    std::vector<LightPrim> lights;
    for (const auto& [path, entry] : scene.lights()) lights.push_back(*entry.prim);
    for (LightPrim& light : lights) {
        light.worldTransform = glm::rotate(glm::dmat4(1.0), radians, glm::dvec3(0, 1, 0)) * light.worldTransform;
        scene.setLight(light);
    }
}

}  // namespace hdhair
