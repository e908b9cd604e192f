#pragma once
// The light a DomeLight gives, in world space, ready for shading: either an
// analytic uniform radiance (an untextured dome) or the SRBF lights fitted
// to its texture (Ren et al. 2010, §3 Eq. 2; SrbfFit.h), which
// hdHair/plan/DomeLighting.h draws.
//
// - Untextured (inputs:texture:file empty): radiance `radianceScale` from
//   every direction, exactly; nothing is fitted.
// - Textured, inputs:texture:format "automatic" or "latlong": the texture is
//   read as a latlong map in Storm's orientation (LatlongDirections.h) and
//   fitted (DomeTextureFitCache.h: once per file and settings). "automatic"
//   reads as latlong: hdHair has no other layout, and Storm (24.08) samples
//   every dome texture as latlong whatever the format says.
// - The texture's radiance is multiplied by `radianceScale`, per channel:
//   UsdLux's inputs:color tints the light, a texture included, as Storm
//   multiplies its dome maps by intensity · 2^exposure · color.
// - The dome's world transform turns the lobes: each centre ξ goes to
//   normalize(M ξ) (domeLightDirectionToWorld), so rotating the dome rotates
//   its lighting the way Storm rotates it. Bandwidths and amplitudes stay:
//   exact for rotations (which is what domes are given); under a non-uniform
//   scale only the centres follow.
// - Bad input falls back to the untextured dome, with a warning at
//   the prim, "<prim>.inputs:texture:file: ..." (or ...:format) naming the file: an
//   unsupported format (mirroredBall, angular, cubeMapVerticalCross, or an
//   unknown token), a missing, unreadable or oversized file (LatlongTexture.h
//   says what is refused). Texels with a NaN, infinite or negative channel
//   are read as 0 and counted in a warning; the texture is still used.
//
// `radianceScale` is the dome's radiance before its texture, intensity ·
// 2^exposure · color (× the blackbody colour when enableColorTemperature):
// the caller passes hdHair/shading's lightRadiance(dome), which keeps this
// folder free of shading (data flows scene -> environment -> shading).

#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/environment/DomeLightSampling.h"
#include "hdHair/environment/DomeTextureFitCache.h"
#include "hdHair/environment/Srbf.h"
#include "hdHair/scene/LightPrim.h"

namespace hdhair {

struct DomeEnvironment {
    std::string lightPath;
    glm::vec3 uniformRadiance{0.0f};  // from every direction (an untextured dome)
    std::vector<Srbf> srbfs;          // world space; amplitudes in radiance, radianceScale applied
    float fitError = 0.0f;            // the fit's relative L2 error (SrbfFit.h); 0 for a uniform dome
    // The reference's view (sampledDomeEnvironment): the dome as distant
    // lights; then uniformRadiance is 0 and srbfs is empty.
    std::vector<SampledDomeLight> sampledLights;
};

// `dome` must be a LightType::Dome light. Warnings go to `diagnostics`.
DomeEnvironment domeEnvironment(const LightPrim& dome, const glm::vec3& radianceScale,
                                const DomeFitSettings& settings, Diagnostics& diagnostics,
                                DomeTextureFitCache& cache = DomeTextureFitCache::process());

// The grid the reference samples a texture on: 0.7° cells, finer than any
// lobe (Srbf.h) and than the fit's 5.6°, so the reference sees the map as it
// is, sun included, not its prefiltered fit.
constexpr int kSampledDomeGridWidth = 512;
constexpr int kSampledDomeGridHeight = 256;

// The dome as the yardstick the SRBF path is measured against
// (domeLighting=sampled): `lightCount` distant lights importance-sampled
// from its radiance (DomeLightSampling.h), in world space. A texture is read
// onto a kSampledDomeGridWidth × kSampledDomeGridHeight grid, unblurred and
// not cached (the reference is slow anyway); an untextured dome (or one whose
// texture cannot be used, with the same warnings as domeEnvironment) is
// sampled as uniform radiance, so the analytic uniform term is measured too.
// The file is read on every call: a reference frame costs minutes.
DomeEnvironment sampledDomeEnvironment(const LightPrim& dome, const glm::vec3& radianceScale, int lightCount,
                                       Diagnostics& diagnostics);

// The environment's radiance arriving from the world direction ω (unit):
// uniformRadiance + Σ_j L_j G(ω; ξ_j, λ_j).
glm::vec3 environmentRadiance(const DomeEnvironment& environment, const glm::vec3& worldDirection);

}  // namespace hdhair
