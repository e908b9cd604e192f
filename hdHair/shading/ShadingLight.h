#pragma once
// A UsdLux light reduced to what hair shading needs: where the light comes
// from and how much irradiance it delivers. Shared by the CPU reference and
// the GPU (hdHair/gl/UniformBlocks.h LightUniforms mirrors it).
//
// Units follow UsdLux: a light's radiance is
//   L = inputs:intensity · 2^inputs:exposure · inputs:color.
// - DistantLight: irradiance E = L at normal incidence, the convention Storm
//   uses; inputs:angle is ignored (hard shadows come with the shadow issue).
// - SphereLight: a point light at its centre; a sphere of radius r seen from
//   distance d delivers E = L·π·r²/d² (exact for d ≥ r). The radius sets the
//   power, it does not soften.
// - RectLight, DiskLight: one-sided point approximations at their centre,
//   emitting along −Z: E = L·A·cosθ/d², with A = width·height or π·r².
// - DomeLight: a constant ambient radiance L on every fibre.
// - inputs:normalize divides out the area (sphere, rect, disk) so that the
//   light's power no longer depends on its size.
// Colour temperature, spot shaping and textures come with the lights issue.

#include <vector>

#include <glm/vec3.hpp>

#include "hdHair/scene/LightPrim.h"

namespace hdhair {

struct ShadingLight {
    bool isLocal = false;             // false: distant (direction), true: positioned
    glm::vec3 directionOrPosition{0.0f, 0.0f, 1.0f};  // unit direction towards a distant light, or position
    glm::vec3 scale{0.0f};            // E for distant lights; E·d² for local ones
    bool oneSided = false;            // rect and disk lights emit only along their axis
    glm::vec3 emissionAxis{0.0f, 0.0f, -1.0f};  // world-space −Z of the light
};

// What the lights of a stage amount to for hair shading.
struct ShadingLights {
    std::vector<ShadingLight> lights;  // distant and local lights
    glm::vec3 ambient{0.0f};           // dome lights' radiance, summed
};

// Radiance of a light before geometry: intensity · 2^exposure · color.
glm::vec3 lightRadiance(const LightPrim& light);

ShadingLights toShadingLights(const std::vector<const LightPrim*>& lights);

// A distant light shining from the camera, used when a stage has no lights
// (as usdview's and usdrecord's default camera light does).
ShadingLight cameraLight(const glm::vec3& directionTowardsCamera);

// Irradiance at `position` and the unit direction towards the light; the
// same formula as lightIrradiance() in shaders/include/lights.glsl.
glm::vec3 irradianceAt(const ShadingLight& light, const glm::vec3& position, glm::vec3* towardsLight);

}  // namespace hdhair
