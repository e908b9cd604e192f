#pragma once
// A UsdLux light with its inputs in USD's units. How each kind is evaluated is
// the shading code's business; the scene only records what was authored.

#include <array>
#include <string>
#include <tuple>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "hdHair/base/TokenTable.h"

namespace hdhair {

enum class LightType { Distant, Sphere, Rect, Disk, Dome };

// The UsdLux schema names.
template <>
struct TokenTable<LightType> {
    static constexpr std::array<TokenName<LightType>, 5> names{{
         {LightType::Distant, "DistantLight"},
         {LightType::Sphere, "SphereLight"},
         {LightType::Rect, "RectLight"},
         {LightType::Disk, "DiskLight"},
         {LightType::Dome, "DomeLight"}}};
};

struct LightPrim {
    std::string path;
    // DomeLight inputs:texture:file, resolved: the embedded reader resolves
    // the asset path against the directory of the layer that authored it, the
    // Hydra plugin takes the host's resolved path (the authored one when the
    // resolver found none). "" for an untextured dome.
    std::string textureFile;
    // DomeLight inputs:texture:format as authored ("automatic", "latlong",
    // "mirroredBall", ...). Kept as a token so that hdHair/environment checks
    // it for every front end alike (DomeEnvironment.h says which it reads).
    std::string textureFormat = "automatic";
    LightType type = LightType::Distant;
    float intensity = 1.0f;                 // inputs:intensity
    float exposure = 0.0f;                  // inputs:exposure (stops)
    glm::vec3 color{1.0f};                  // inputs:color
    bool enableColorTemperature = false;    // inputs:enableColorTemperature
    float colorTemperature = 6500.0f;       // inputs:colorTemperature (K)
    bool normalize = false;                 // inputs:normalize
    float angle = 0.53f;                    // DistantLight inputs:angle (degrees)
    float radius = 0.5f;                    // Sphere/Disk inputs:radius
    float width = 1.0f, height = 1.0f;      // RectLight inputs:width/height
    float coneAngle = 90.0f;                // shaping:cone:angle (degrees)
    float coneSoftness = 0.0f;              // shaping:cone:softness
    // ShadowAPI inputs:shadow:enable (USD's fallback: true): the light casts
    // hair self-shadows (deep opacity maps, hdHair/render/README.md).
    bool shadowEnable = true;
    glm::dmat4 worldTransform{1.0};         // lights emit along their -Z axis
    bool visible = true;
    // A light the host adds at the camera (usdview's and usdrecord's default
    // camera light), not one of the stage's. It is used or not by the
    // cameraLight setting, like the engine's own camera light, so a stage
    // looks the same in hdhair-record, usdrecord and usdview.
    bool hostCameraLight = false;
    // Every member, for operator==: a scene keeps a prim's version when it is
    // set again unchanged (hdhair-record --frames), so nothing is prepared,
    // uploaded or shadowed again. A member added above must be added here;
    // the size check after the struct is there to say so.
    auto fields() const {
        return std::tie(path, textureFile, textureFormat, type, intensity, exposure, color, enableColorTemperature,
                        colorTemperature, normalize, angle, radius, width, height, coneAngle, coneSoftness, shadowEnable,
                        worldTransform, visible, hostCameraLight);
    }
    bool operator==(const LightPrim& other) const { return fields() == other.fields(); }
    bool operator!=(const LightPrim& other) const { return !(*this == other); }
};
static_assert(sizeof(LightPrim) == 296, "a member was added to LightPrim: add it to fields() too (x86-64 size)");

}  // namespace hdhair
