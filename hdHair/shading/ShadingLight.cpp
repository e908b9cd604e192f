#include "hdHair/shading/ShadingLight.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/trigonometric.hpp>

#include "hdHair/environment/Srbf.h"
#include "hdHair/shading/ColorTemperature.h"

namespace hdhair {

glm::vec3 lightRadiance(const LightPrim& light) {
    glm::vec3 color = light.color;
    if (light.enableColorTemperature) color *= blackbodyColor(light.colorTemperature);
    return light.intensity * std::exp2(light.exposure) * color;
}

namespace {

glm::vec3 transformDirection(const glm::dmat4& m, const glm::dvec3& d) {
    glm::dvec3 v = glm::dvec3(m * glm::dvec4(d, 0.0));
    double length = glm::length(v);
    return length > 0.0 ? glm::vec3(v / length) : glm::vec3(0.0f, 0.0f, 1.0f);
}

// UsdLuxShapingAPI's cone; see ShadingLight.h.
void setCone(const LightPrim& light, ShadingLight* shading) {
    float angle = light.coneAngle;
    if (!(angle < 90.0f)) return;  // also NaN
    angle = std::max(angle, 0.0f);
    float softness = std::isnan(light.coneSoftness) ? 0.0f : std::clamp(light.coneSoftness, 0.0f, 1.0f);
    shading->shaped = true;
    shading->coneCosOuter = std::cos(glm::radians(angle));
    shading->coneCosInner = std::cos(glm::radians(angle * (1.0f - softness)));
}

float emitterArea(const LightPrim& light) {
    switch (light.type) {
    case LightType::Sphere:
    case LightType::Disk: return glm::pi<float>() * light.radius * light.radius;
    case LightType::Rect: return light.width * light.height;
    default: return 1.0f;
    }
}

}  // namespace

ShadingLights toShadingLights(const std::vector<const LightPrim*>& lights) {
    ShadingLights result;
    for (const LightPrim* light : lights) {
        if (!light->visible) continue;
        glm::vec3 radiance = lightRadiance(*light);
        if (light->type == LightType::Dome) {
            result.ambient += radiance;
            continue;
        }
        ShadingLight shading;
        shading.castsShadow = light->shadowEnable;
        shading.path = light->path;
        if (light->type == LightType::Distant) {
            // Lights emit along their −Z axis, so the light lies towards +Z.
            shading.directionOrPosition = transformDirection(light->worldTransform, {0.0, 0.0, 1.0});
            shading.scale = radiance;
        } else {
            shading.isLocal = true;
            shading.directionOrPosition = glm::vec3(light->worldTransform[3]);
            // A sphere, rect or disk of area A delivers E·d² = L·A (π r² for the
            // sphere's projected disc); normalize makes it independent of A.
            float area = light->normalize ? 1.0f : emitterArea(*light);
            shading.scale = radiance * area;
            shading.oneSided = light->type != LightType::Sphere;
            shading.emissionAxis = transformDirection(light->worldTransform, {0.0, 0.0, -1.0});
            setCone(*light, &shading);
        }
        result.lights.push_back(shading);
    }
    return result;
}

ShadingLight cameraLight(const glm::vec3& directionTowardsCamera, bool castsShadow) {
    ShadingLight light;
    light.directionOrPosition = glm::normalize(directionTowardsCamera);
    light.scale = glm::vec3(1.0f);
    light.castsShadow = castsShadow;
    return light;
}

float coneFalloff(const ShadingLight& light, float cosAngle) {
    if (!light.shaped) return 1.0f;
    if (light.coneCosInner <= light.coneCosOuter) return cosAngle >= light.coneCosOuter ? 1.0f : 0.0f;
    float t = std::clamp((cosAngle - light.coneCosOuter) / (light.coneCosInner - light.coneCosOuter), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);  // GLSL smoothstep
}

glm::vec3 irradianceAt(const ShadingLight& light, const glm::vec3& position, glm::vec3* towardsLight) {
    if (!light.isLocal) {
        *towardsLight = light.directionOrPosition;
        return light.isSrbf() ? light.scale * srbfIntegral(light.srbfBandwidth) : light.scale;
    }
    glm::vec3 offset = light.directionOrPosition - position;
    float distanceSquared = std::max(glm::dot(offset, offset), 1e-12f);
    *towardsLight = offset / std::sqrt(distanceSquared);
    float cosAngle = glm::dot(-*towardsLight, light.emissionAxis);
    float facing = light.oneSided ? std::max(0.0f, cosAngle) : 1.0f;
    return light.scale * (facing * coneFalloff(light, cosAngle) / distanceSquared);
}

}  // namespace hdhair
