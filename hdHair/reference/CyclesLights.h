#pragma once
// UsdLux lights in Cycles' units, so that the path-traced reference is lit
// exactly as hdHair's frame is (docs/cycles-reference.md, "Lights").
//
// hdHair reduces every light to what it delivers (ShadingLight.h): a distant
// light's irradiance E at normal incidence, and a local light's radiant
// intensity I = E·d² along its axis. Cycles is driven by the same two
// quantities, measured here with a white Lambertian plane
// (docs/cycles-reference.md gives the renders):
//   sun of strength S:               E = S                (W/m²)
//   point or spot light of power P:  I = P / (4π)         (W/sr, every direction)
//   area light (any shape) of P:     I = P / 4            (W/sr, on its axis; cos θ off it)
// so S = E, P_point = 4π·I and P_area = 4·I. USD's intensity, exposure,
// colour, colour temperature and normalize therefore reach Cycles through
// the one place hdHair evaluates them (toShadingLights), and what differs is
// only what hdHair approximates: Cycles gives a sphere, rect or disk light
// its real extent (soft shadows, the falloff near the emitter) and a distant
// light its angular diameter (inputs:angle), where hdHair shades points.
// Cones (UsdLuxShapingAPI) become spot lights for sphere lights; Cycles 3.4
// has no cone for area lights, so a shaped rect or disk light warns and
// emits unshaped. Dome lights become the world (CyclesWorld below).

#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "hdHair/image/ColorSpaces.h"
#include "hdHair/scene/LightPrim.h"

namespace hdhair {

class Diagnostics;
class Scene;
struct CameraView;

struct CyclesLight {
    enum class Kind { Sun, Point, Spot, Area };
    Kind kind = Kind::Sun;
    std::string path;             // the USD light ("" for hdHair's camera light)
    glm::dmat4 lightToWorld{1.0}; // rotation and translation only; the light emits along −Z
    glm::vec3 strength{0.0f};     // Sun: irradiance (W/m²); others: power P (W) per channel
    float radius = 0.0f;          // Point, Spot: the sphere's radius (Cycles' shadow_soft_size)
    float angle = 0.0f;           // Sun: angular diameter (radians)
    bool disk = false;            // Area: a disk of diameter sizeX, else a sizeX × sizeY rectangle
    float sizeX = 0.0f, sizeY = 0.0f;
    float spotSize = 0.0f;        // Spot: full cone angle (radians)
    float spotBlend = 0.0f;       // Spot: Cycles' spot_blend, from shaping:cone:softness
    bool castShadow = true;
};

// A dome light as Cycles' world: radiance times the texture (or uniform).
struct CyclesDome {
    std::string path;
    glm::vec3 radiance{0.0f};  // intensity · 2^exposure · colour (· blackbody)
    std::string textureFile;   // "" for a uniform dome
    // World direction ω to the vector Blender's equirectangular lookup takes:
    // USD's latlong frame (LatlongDirections.h: +Y the top pole, +Z the
    // image's centre, +X a quarter to the left of it) after the dome's
    // inverse transform, permuted into Blender's (+Z the top pole, +X the
    // centre, +Y a quarter to the left): D = P · M⁻¹ · ω, rows of P·M⁻¹ here.
    glm::dmat3 worldToTexture{1.0};
};

struct CyclesLighting {
    std::vector<CyclesLight> lights;
    std::vector<CyclesDome> domes;
};

// The visible lights of `scene` in Cycles' units, in the rendering space.
// `addCameraLight`: the frame uses hdHair's camera light (a stage without
// lights, LightPlan::cameraLight); it becomes a sun at the camera, casting
// shadows with `cameraLightShadows` as hdHair's does. Problems
// that change the picture (a cone Cycles cannot make, a dome texture format
// other than latlong) warn through `diagnostics`, naming the light.
CyclesLighting cyclesLighting(const Scene& scene, const CameraView& camera, bool addCameraLight,
                              bool cameraLightShadows, RenderingSpace space, Diagnostics& diagnostics);

}  // namespace hdhair
