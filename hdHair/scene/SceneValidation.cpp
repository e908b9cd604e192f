#include "hdHair/scene/SceneValidation.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include <fmt/format.h>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/base/InputError.h"

namespace hdhair {

namespace {

// Replaces a value that is not finite, or outside [low, high], by
// `replacement`, with a warning saying which and why. `replacementText` names
// the replacement ("USD's fallback 1", "0").
class LightRepairs {
public:
    LightRepairs(LightPrim& light, const std::string& where, Diagnostics& diagnostics)
        : light_(light), where_(where), diagnostics_(diagnostics) {}

    // Not finite: `fallback` (USD's, as if unauthored).
    void finiteOr(float& value, const char* attribute, float fallback) {
        if (std::isfinite(value)) return;
        warn(attribute, fmt::format("{} is not a number; using USD's fallback {}", value, fallback));
        value = fallback;
    }
    // Below `low` (after finiteOr): `replacement`, saying `why`.
    void atLeast(float& value, const char* attribute, float low, float replacement, const char* why) {
        if (value >= low) return;
        warn(attribute, fmt::format("{} is {}; using {}", value, why, replacement));
        value = replacement;
    }
    void warn(const char* attribute, const std::string& message) {
        diagnostics_.warn(where_, light_.path + ".inputs:" + attribute + ": " + message);
    }

private:
    LightPrim& light_;
    const std::string& where_;
    Diagnostics& diagnostics_;
};

// The emitter's area as shading takes it (ShadingLight.cpp emitterArea), in
// double so that the overflow check itself cannot overflow.
double emitterArea(const LightPrim& light) {
    if (light.normalize) return 1.0;
    switch (light.type) {
    case LightType::Sphere:
    case LightType::Disk: return 3.141592653589793 * double(light.radius) * double(light.radius);
    case LightType::Rect: return double(light.width) * double(light.height);
    default: return 1.0;
    }
}

}  // namespace

bool isFiniteTransform(const glm::dmat4& matrix) {
    for (int column = 0; column < 4; ++column)
        for (int row = 0; row < 4; ++row)
            if (!std::isfinite(matrix[column][row])) return false;
    return true;
}

std::string transformProblem(const std::string& primPath, const glm::dmat4& worldTransform) {
    if (isFiniteTransform(worldTransform)) return std::string();
    return primPath + ": the world transform is not finite (a NaN or infinite xformOp value, here or on an "
                      "ancestor, or a singular matrix under \"!invert!\"); prim not drawn";
}

bool repairLight(LightPrim& light, const std::string& where, Diagnostics& diagnostics) {
    if (!isFiniteTransform(light.worldTransform)) {
        diagnostics.warn(where, light.path + ": the world transform is not finite (a NaN or infinite xformOp "
                                             "value, or a singular matrix under \"!invert!\"); light skipped");
        return false;
    }
    // Distant and local lights need their -Z axis (a dome's light has no
    // direction): a zero scale along it leaves no direction to shine in.
    const glm::dvec3 axis(light.worldTransform * glm::dvec4(0.0, 0.0, -1.0, 0.0));
    if (light.type != LightType::Dome && !(axis.x != 0.0 || axis.y != 0.0 || axis.z != 0.0)) {
        diagnostics.warn(where, light.path + ": the world transform scales the light's -Z axis to nothing, so it "
                                             "has no direction; light skipped");
        return false;
    }
    LightRepairs repair(light, where, diagnostics);
    const float fallbackIntensity = light.type == LightType::Distant ? 50000.0f : 1.0f;
    repair.finiteOr(light.intensity, "intensity", fallbackIntensity);
    repair.atLeast(light.intensity, "intensity", 0.0f, 0.0f, "negative (negative emission would subtract light)");
    repair.finiteOr(light.exposure, "exposure", 0.0f);
    if (!std::isfinite(light.color.r) || !std::isfinite(light.color.g) || !std::isfinite(light.color.b)) {
        repair.warn("color", fmt::format("({}, {}, {}) is not a colour of finite numbers; using USD's fallback "
                                         "(1, 1, 1)",
                                         light.color.r, light.color.g, light.color.b));
        light.color = glm::vec3(1.0f);
    }
    if (light.color.r < 0.0f || light.color.g < 0.0f || light.color.b < 0.0f) {
        repair.warn("color", fmt::format("({}, {}, {}) has a negative component (negative emission would subtract "
                                         "light); negative components are 0",
                                         light.color.r, light.color.g, light.color.b));
        light.color = glm::max(light.color, glm::vec3(0.0f));
    }
    repair.finiteOr(light.colorTemperature, "colorTemperature", 6500.0f);
    if (light.colorTemperature <= 0.0f) {
        repair.warn("colorTemperature", fmt::format("{} K is not a temperature; using USD's fallback 6500",
                                                    light.colorTemperature));
        light.colorTemperature = 6500.0f;
    }
    repair.finiteOr(light.angle, "angle", 0.53f);
    repair.atLeast(light.angle, "angle", 0.0f, 0.53f, "negative; USD's fallback");
    repair.finiteOr(light.radius, "radius", 0.5f);
    repair.atLeast(light.radius, "radius", 0.0f, 0.5f, "negative; USD's fallback");
    repair.finiteOr(light.width, "width", 1.0f);
    repair.atLeast(light.width, "width", 0.0f, 1.0f, "negative; USD's fallback");
    repair.finiteOr(light.height, "height", 1.0f);
    repair.atLeast(light.height, "height", 0.0f, 1.0f, "negative; USD's fallback");
    repair.finiteOr(light.coneAngle, "shaping:cone:angle", 90.0f);
    repair.atLeast(light.coneAngle, "shaping:cone:angle", 0.0f, 0.0f, "negative");
    repair.finiteOr(light.coneSoftness, "shaping:cone:softness", 0.0f);
    if (light.coneSoftness < 0.0f || light.coneSoftness > 1.0f) {
        const float clamped = std::clamp(light.coneSoftness, 0.0f, 1.0f);
        repair.warn("shaping:cone:softness",
                    fmt::format("{} is outside [0, 1]; using {}", light.coneSoftness, clamped));
        light.coneSoftness = clamped;
    }
    // The blackbody colour has luminance 1 and components below 2
    // (ColorTemperature.h), so this bounds what shading multiplies.
    const double strongest = double(std::max({light.color.r, light.color.g, light.color.b}));
    const double power = double(light.intensity) * std::exp2(double(light.exposure)) * strongest *
                         (light.enableColorTemperature ? 2.0 : 1.0) * emitterArea(light);
    if (!(power <= double(FLT_MAX))) {
        diagnostics.warn(where, fmt::format("{}.inputs:intensity: {} x 2^{} (exposure) x colour x area is beyond "
                                            "float range; light skipped",
                                            light.path, light.intensity, light.exposure));
        return false;
    }
    return true;
}

CameraPrim checkedCamera(const CameraPrim& camera, const std::string& where, Diagnostics& diagnostics) {
    auto refuse = [&](const char* attribute, float value, const char* why) {
        throw InputError(fmt::format("{}: {}.{}: {} is {}; the camera cannot be used", where, camera.path, attribute,
                                     value, why));
    };
    auto positive = [&](const char* attribute, float value) {
        if (!std::isfinite(value)) refuse(attribute, value, "not a number");
        if (value <= 0.0f) refuse(attribute, value, "not a positive length");
    };
    // An orthographic camera's view is its apertures; focal length is unused.
    if (camera.projection == Projection::Perspective) positive("focalLength", camera.focalLength);
    positive("horizontalAperture", camera.horizontalAperture);
    positive("verticalAperture", camera.verticalAperture);
    if (!std::isfinite(camera.horizontalApertureOffset))
        refuse("horizontalApertureOffset", camera.horizontalApertureOffset, "not a number");
    if (!std::isfinite(camera.verticalApertureOffset))
        refuse("verticalApertureOffset", camera.verticalApertureOffset, "not a number");
    if (!isFiniteTransform(camera.worldTransform))
        throw InputError(where + ": " + camera.path +
                         ": the world transform is not finite (a NaN or infinite xformOp value, or a singular matrix "
                         "under \"!invert!\"); the camera cannot be used");
    // Valid, yet a frame no one means: at 960 pixels wide a 1:10000 aperture
    // is one row tall, and 10000:1 is past any image size. Said, with the
    // shape it implies, so that a near-empty frame is not a mystery.
    const double aspect = double(camera.horizontalAperture) / double(camera.verticalAperture);
    if (aspect > kMostApertureRatio || aspect < 1.0 / kMostApertureRatio)
        diagnostics.warn(where, fmt::format("{}.horizontalAperture, {}.verticalAperture: ({:.6g}, {:.6g}) make an image {:.4g} "
                                            "times as wide as it is tall; check the apertures",
                                            camera.path, camera.path, camera.horizontalAperture,
                                            camera.verticalAperture, aspect));
    CameraPrim checked = camera;
    const glm::vec2 range = camera.clippingRange;
    if (!std::isfinite(range.x) || !std::isfinite(range.y) || range.x <= 0.0f || range.y <= range.x) {
        const char* why = !std::isfinite(range.x) || !std::isfinite(range.y) ? "not finite"
                          : range.x <= 0.0f                                ? "a near distance that is not positive"
                                                                           : "far not beyond near";
        diagnostics.warn(where, fmt::format("{}.clippingRange: ({}, {}) is {}; using USD's fallback (1, 1000000)",
                                            camera.path, range.x, range.y, why));
        checked.clippingRange = glm::vec2(1.0f, 1000000.0f);
    }
    return checked;
}

}  // namespace hdhair
