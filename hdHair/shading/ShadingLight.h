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
// - DomeLight: by default SRBF lights and an analytic uniform term, which
//   hdHair/plan/DomeLighting.h adds; toShadingLights gives the old flat
//   ambient radiance L (the domeLighting=ambient setting).
// - An SRBF light (srbfBandwidth > 0) is one Gaussian lobe of a dome
//   (hdHair/environment/Srbf.h): directionOrPosition is its centre ξ, scale
//   its amplitude L_j (radiance). Hair reads its response from the SRBF
//   convolution tables; irradianceAt (meshes) treats it as the distant
//   light it becomes as λ → ∞, of irradiance L_j ∫G dω (Ren et al. 2010 §3).
// - inputs:normalize divides out the area (sphere, rect, disk) so that the
//   light's power no longer depends on its size.
// - inputs:enableColorTemperature multiplies inputs:color by the blackbody
//   colour of inputs:colorTemperature (ColorTemperature.h: linear Rec.709,
//   luminance 1, temperatures clamped to [1000, 10000] K), as UsdLux does.
// - UsdLuxShapingAPI's cone (sphere, rect and disk lights): light leaves
//   only within inputs:shaping:cone:angle (degrees, half-angle) of the
//   light's −Z axis. inputs:shaping:cone:softness s in [0, 1] fades it in
//   from the edge inwards: full emission within angle·(1 − s), a smoothstep
//   in cosθ between cos(angle·(1 − s)) and cos(angle), nothing beyond the
//   angle; s = 0 is a hard edge (cosθ ≥ cos(angle) is inside). Angles of
//   90° and more leave a light unshaped: 90° is ShapingAPI's fallback and
//   must not cut a sphere light in half, and a rect or disk light emits into
//   that hemisphere anyway. Distant and dome lights are never shaped. (Storm
//   in 24.08 applies the cone to rect and disk lights only, as a hard
//   cutoff, and ignores the softness.)
// Textures, focus and IES profiles are not supported.

#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "hdHair/scene/LightPrim.h"

namespace hdhair {

struct ShadingLight {
    bool isLocal = false;             // false: distant (direction), true: positioned
    glm::vec3 directionOrPosition{0.0f, 0.0f, 1.0f};  // unit direction towards a distant light, or position
    glm::vec3 scale{0.0f};            // E for distant lights; E·d² for local ones
    bool oneSided = false;            // rect and disk lights emit only along their axis
    glm::vec3 emissionAxis{0.0f, 0.0f, -1.0f};  // world-space −Z of the light; also the cone's axis
    bool shaped = false;              // a ShapingAPI cone narrower than 90° (local lights only)
    float coneCosOuter = 0.0f;        // cos(shaping:cone:angle): no light beyond it
    float coneCosInner = 0.0f;        // cos(angle·(1 − softness)): full light within it
    bool castsShadow = true;          // inputs:shadow:enable
    std::string path;                 // the light prim it came from ("" for the engine's camera light)
    float srbfBandwidth = 0.0f;       // > 0: an SRBF light of bandwidth λ (isLocal false)
    bool isSrbf() const { return srbfBandwidth > 0.0f; }
};

// What the lights of a stage amount to for hair shading.
struct ShadingLights {
    std::vector<ShadingLight> lights;  // distant and local lights
    glm::vec3 ambient{0.0f};           // dome lights' radiance, summed: a flat term (domeLighting=ambient)
    // Untextured domes' radiance, summed, shaded as the fibre model's exact
    // response to uniform light (domeLighting=srbf; hdHair/plan/DomeLighting.h).
    glm::vec3 uniformDome{0.0f};
    bool uniformDomeCastsShadow = false;  // one of those domes has inputs:shadow:enable
};

// Radiance of a light before geometry: intensity · 2^exposure · color, times
// blackbodyColor(colorTemperature) when enableColorTemperature is on.
glm::vec3 lightRadiance(const LightPrim& light);

// The cone's attenuation in [0, 1] for a direction whose cosine to the
// light's emission axis is `cosAngle`; 1 for an unshaped light. The same
// formula as lightCone() in shaders/include/lights.glsl.
float coneFalloff(const ShadingLight& light, float cosAngle);

ShadingLights toShadingLights(const std::vector<const LightPrim*>& lights);

// A distant light shining from the camera, used when a stage has no lights
// (as usdview's and usdrecord's default camera light does). It casts
// shadows only when asked (the cameraLightShadows setting): a light at the
// eye darkens only what the eye cannot see behind the hair, and hosts'
// camera lights (Storm's default light) cast none.
ShadingLight cameraLight(const glm::vec3& directionTowardsCamera, bool castsShadow);

// Irradiance at `position` and the unit direction towards the light, with
// the one-sided emitters' cosine and the cone applied; the same formula as
// lightIrradiance() in shaders/include/lights.glsl.
glm::vec3 irradianceAt(const ShadingLight& light, const glm::vec3& position, glm::vec3* towardsLight);

}  // namespace hdhair
