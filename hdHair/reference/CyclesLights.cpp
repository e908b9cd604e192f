#include "hdHair/reference/CyclesLights.h"

#include <cmath>

#include <glm/gtc/constants.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/plan/CameraView.h"
#include "hdHair/plan/LightPlanner.h"
#include "hdHair/scene/Scene.h"
#include "hdHair/shading/ShadingLight.h"

namespace hdhair {
namespace {

// A light-to-world matrix with unit axes: Cycles takes a light's size from
// its parameters, as hdHair does, not from its transform's scale.
glm::dmat4 rigid(const glm::dmat4& transform) {
    glm::dmat4 result(1.0);
    glm::dvec3 z = glm::dvec3(transform[2]);
    glm::dvec3 y = glm::dvec3(transform[1]);
    if (glm::length(z) == 0.0 || !std::isfinite(glm::length(z))) z = {0.0, 0.0, 1.0};
    z = glm::normalize(z);
    glm::dvec3 x = glm::cross(y, z);
    if (glm::length(x) < 1e-12) x = std::abs(z.x) < 0.9 ? glm::cross(glm::dvec3(1.0, 0.0, 0.0), z)
                                                        : glm::cross(glm::dvec3(0.0, 1.0, 0.0), z);
    x = glm::normalize(x);
    y = glm::cross(z, x);
    result[0] = glm::dvec4(x, 0.0);
    result[1] = glm::dvec4(y, 0.0);
    result[2] = glm::dvec4(z, 0.0);
    result[3] = glm::dvec4(glm::dvec3(transform[3]), 1.0);
    return result;
}

// A sun whose −Z points away from `towardsLight`.
glm::dmat4 sunFacing(const glm::vec3& towardsLight) {
    glm::dmat4 frame(1.0);
    frame[2] = glm::dvec4(glm::dvec3(towardsLight), 0.0);
    frame[1] = glm::dvec4(0.0, 1.0, 0.0, 0.0);
    if (std::abs(towardsLight.y) > 0.99f) frame[1] = glm::dvec4(0.0, 0.0, 1.0, 0.0);
    return rigid(frame);
}

CyclesLight fromShadingLight(const LightPrim& prim, const ShadingLight& shading, const glm::mat3& toSpace,
                             Diagnostics& diagnostics) {
    CyclesLight light;
    light.path = prim.path;
    light.castShadow = prim.shadowEnable;
    const glm::vec3 scale = toSpace * shading.scale;
    switch (prim.type) {
        case LightType::Distant:
            light.kind = CyclesLight::Kind::Sun;
            light.lightToWorld = sunFacing(shading.directionOrPosition);
            light.strength = scale;  // S = E
            light.angle = std::isfinite(prim.angle) ? std::max(prim.angle, 0.0f) * glm::pi<float>() / 180.0f : 0.0f;
            break;
        case LightType::Sphere:
            light.kind = shading.shaped ? CyclesLight::Kind::Spot : CyclesLight::Kind::Point;
            light.lightToWorld = rigid(prim.worldTransform);
            light.strength = 4.0f * glm::pi<float>() * scale;  // P = 4π I
            light.radius = std::max(prim.radius, 0.0f);
            if (shading.shaped) {
                light.spotSize = 2.0f * std::acos(std::clamp(shading.coneCosOuter, -1.0f, 1.0f));
                light.spotBlend = std::clamp(prim.coneSoftness, 0.0f, 1.0f);
            }
            break;
        case LightType::Rect:
        case LightType::Disk:
            light.kind = CyclesLight::Kind::Area;
            light.lightToWorld = rigid(prim.worldTransform);
            light.strength = 4.0f * scale;  // P = 4 I
            light.disk = prim.type == LightType::Disk;
            light.sizeX = light.disk ? 2.0f * std::max(prim.radius, 0.0f) : std::max(prim.width, 0.0f);
            light.sizeY = light.disk ? light.sizeX : std::max(prim.height, 0.0f);
            if (shading.shaped)
                diagnostics.warn(prim.path, "shaping:cone:angle: Cycles 3.4 has no cone for area lights; the "
                                            "reference lets this light emit into its whole hemisphere");
            break;
        case LightType::Dome: break;
    }
    return light;
}

CyclesDome domeOf(const LightPrim& prim, const glm::mat3& toSpace, Diagnostics& diagnostics) {
    CyclesDome dome;
    dome.path = prim.path;
    dome.radiance = toSpace * lightRadiance(prim);
    if (!prim.textureFile.empty()) {
        if (prim.textureFormat != "automatic" && prim.textureFormat != "latlong")
            diagnostics.warn(prim.path, "inputs:texture:format '" + prim.textureFormat +
                                            "': the reference reads latlong textures only; this dome is uniform "
                                            "there");
        else
            dome.textureFile = prim.textureFile;
    }
    // D = P · M⁻¹ · ω with P: (x, y, z) -> (z, x, y) (USD latlong to Blender's).
    const glm::dmat3 worldToDome = glm::inverse(glm::dmat3(prim.worldTransform));
    glm::dmat3 permutation(0.0);
    permutation[2][0] = 1.0;  // D.x = d.z
    permutation[0][1] = 1.0;  // D.y = d.x
    permutation[1][2] = 1.0;  // D.z = d.y
    dome.worldToTexture = permutation * worldToDome;
    return dome;
}

}  // namespace

CyclesLighting cyclesLighting(const Scene& scene, const CameraView& camera, bool addCameraLight,
                              bool cameraLightShadows, RenderingSpace space, Diagnostics& diagnostics) {
    CyclesLighting lighting;
    const glm::mat3 toSpace = rec709To(space);
    for (const auto& [path, entry] : scene.lights()) {
        const LightPrim& prim = *entry.prim;
        if (!prim.visible || prim.hostCameraLight) continue;
        if (prim.type == LightType::Dome) {
            lighting.domes.push_back(domeOf(prim, toSpace, diagnostics));
            continue;
        }
        ShadingLights shading = toShadingLights({&prim});
        if (shading.lights.size() == 1)
            lighting.lights.push_back(fromShadingLight(prim, shading.lights.front(), toSpace, diagnostics));
    }
    if (addCameraLight) {
        const ShadingLight shading = cameraLightOf(camera, cameraLightShadows);
        CyclesLight light;
        light.kind = CyclesLight::Kind::Sun;
        light.lightToWorld = sunFacing(shading.directionOrPosition);
        light.strength = toSpace * shading.scale;
        light.castShadow = shading.castsShadow;
        lighting.lights.push_back(light);
    }
    return lighting;
}

}  // namespace hdhair
