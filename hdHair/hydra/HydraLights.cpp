#include "hdHair/hydra/HydraLights.h"

namespace hdhair::hydra {
namespace {

float number(const LightParameterLookup& parameter, const char* name, float fallback) {
    std::optional<std::vector<double>> value = parameter(name);
    return (value && !value->empty()) ? float((*value)[0]) : fallback;
}

}  // namespace

LightPrim lightFromHydra(const std::string& path, LightType type, bool hostCameraLight,
                         const LightParameterLookup& parameter, const glm::dmat4& lightToWorld,
                         const HydraDomeTexture& texture) {
    LightPrim light;
    light.path = path;
    light.type = type;
    light.worldTransform = lightToWorld;
    light.hostCameraLight = hostCameraLight;
    // UsdLux's fallbacks apply where the host gives nothing.
    light.intensity = hostCameraLight ? 1.0f : number(parameter, "intensity", light.intensity);
    light.exposure = hostCameraLight ? 0.0f : number(parameter, "exposure", light.exposure);
    if (std::optional<std::vector<double>> color = parameter("color"); color && color->size() >= 3)
        light.color = glm::vec3(float((*color)[0]), float((*color)[1]), float((*color)[2]));
    light.normalize = number(parameter, "normalize", 0.0f) != 0.0f;
    light.enableColorTemperature = number(parameter, "enableColorTemperature", 0.0f) != 0.0f;
    light.colorTemperature = number(parameter, "colorTemperature", light.colorTemperature);
    light.angle = number(parameter, "angle", light.angle);
    light.radius = number(parameter, "radius", light.radius);
    light.width = number(parameter, "width", light.width);
    light.height = number(parameter, "height", light.height);
    light.coneAngle = number(parameter, "shaping:cone:angle", light.coneAngle);
    light.coneSoftness = number(parameter, "shaping:cone:softness", light.coneSoftness);
    light.shadowEnable = number(parameter, "shadow:enable", 1.0f) != 0.0f;
    if (type == LightType::Dome) {
        light.textureFile = texture.file;
        if (!texture.format.empty()) light.textureFormat = texture.format;
    }
    return light;
}

}  // namespace hdhair::hydra
