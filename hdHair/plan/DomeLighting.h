#pragma once
// How DomeLights light a frame (the domeLighting setting), after Ren, Zhou,
// Li, Hua & Guo 2010, "Interactive Hair Rendering under Environment
// Lighting" (digest 002):
// - srbf (default): a textured dome is its fit (hdHair/environment/
//   DomeEnvironment.h), domeLights Gaussian SRBF lights, each added to the
//   frame's lights as a ShadingLight with srbfBandwidth > 0. They go through
//   the ordinary light batches (lightsPerPass a pass), and a strand reads
//   each one's response from its material's SRBF-convolution table, eq. (4):
//   L_j T̃_j I(ωo; ξ_j, λ_j). An untextured dome (or one whose texture
//   failed) is ShadingLights::uniformDome: the fibre model's exact response
//   to uniform radiance (hdHair/shading/SrbfUniformDome.h), in the first
//   batch.
// - ambient: the old flat term, radiance × colour (toShadingLights), kept to
//   compare with.
// - sampled: the reference the srbf mode is measured against:
//   each dome, textured or not, as domeSampledLights distant lights
//   importance-sampled from its radiance (sampledDomeEnvironment,
//   DomeLightSampling.h), each casting its own deep opacity map when the dome
//   casts shadows, through the ordinary light and shadow passes. Slow
//   (minutes a frame is fine: it serves tests on small images and
//   hdhair-bench --table dome), and refused rather than drawn wrong: when
//   shadowMemoryMB cannot hold every sampled light's map the frame fails
//   (Renderer) instead of leaving lights unshadowed.
// Self-shadowing (T̃_j, Ren §5): the domeShadowLights strongest SRBFs of a
// dome that casts shadows (amplitude summed over RGB × ∫G dω) get their own
// deep opacity map, as distant lights from ξ_j (the ordinary shadow
// passes); every other SRBF of that dome reads the map of the shadowed SRBF
// nearest to it in direction (ShadowPlan::sharedMaps). The lookup widens
// with depth behind the first hair by the lobe's support angle
// (srbfShadowTransmittance in shaders/include/shadows.glsl): by default
// (domeShadowFilter=mipmap) through the paper's convolution optical depth
// map, a mip chain of the opacity layers (the opacityMipmaps pass) where the
// paper builds summed-area tables; or (taps) nine lookups of transmittance.
// A dome with shadow:enable false and the uniform term are unshadowed.

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "hdHair/environment/DomeEnvironment.h"
#include "hdHair/plan/SettingTokens.h"
#include "hdHair/shading/ShadingLight.h"

namespace hdhair {

class Diagnostics;
class RenderSettings;
class Scene;


// The visible DomeLights of `scene` (path order) as world-space lighting,
// fitted with domeLights SRBFs through the process's fit cache: a fit per
// texture file and setting, then a `stat` a frame; under domeLighting=sampled,
// as domeSampledLights sampled lights (sampledDomeEnvironment). A texture
// that cannot be used warns (naming the prim and the file) and the dome
// comes back uniform. Empty under domeLighting=ambient.
std::vector<DomeEnvironment> frameDomeEnvironments(const Scene& scene, const RenderSettings& settings,
                                                   Diagnostics& diagnostics);

// What the plan made of one dome, for --explain and the tests.
struct PlannedDome {
    std::string path;
    size_t firstLight = 0;      // its first SRBF in ShadingLights::lights
    size_t srbfLights = 0;      // 0: a uniform dome, shaded analytically
    size_t shadowedLights = 0;  // SRBFs with a map of their own
    size_t sampledLights = 0;   // domeLighting=sampled: its distant lights (all shadowed when it casts)
    float fitError = 0.0f;
    std::string describe(size_t lightsPerPass) const;
};

// Adds the scene's visible domes to `lights` as the srbf or sampled mode
// shades them. A sampled dome (DomeEnvironment::sampledLights) becomes its
// distant lights ("<dome> sample <k>"), casting shadows when the dome does.
// Otherwise, as the srbf mode shades them:
// each SRBF as a ShadingLight (a dome's strongest first; path
// "<dome> srbf <j>"), uniform radiance to lights.uniformDome. A visible dome
// that `domes` does not list counts as untextured (its radiance, uniform).
// `sharedMaps` gets, for each SRBF that casts no map of its own but whose
// dome shadows, the light whose map it reads.
std::vector<PlannedDome> addDomeLights(const Scene& scene, const std::vector<DomeEnvironment>& domes,
                                       int shadowedPerDome, ShadingLights& lights,
                                       std::map<size_t, size_t>& sharedMaps);

}  // namespace hdhair
