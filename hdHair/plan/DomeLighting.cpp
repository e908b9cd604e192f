#include "hdHair/plan/DomeLighting.h"

#include <algorithm>
#include <numeric>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/plan/RenderSettings.h"
#include "hdHair/scene/Scene.h"

namespace hdhair {

namespace {

bool isDrawnDome(const LightPrim& light) {
    return light.type == LightType::Dome && light.visible && !light.hostCameraLight;
}

// What a lobe adds to the scene: its amplitude over RGB times its solid
// angle (∫G dω, Srbf.h), the power of the distant light it tends to.
float lobePower(const Srbf& srbf) {
    return (srbf.amplitude.r + srbf.amplitude.g + srbf.amplitude.b) * srbfIntegral(srbf.lobe.bandwidth);
}

}  // namespace

std::vector<DomeEnvironment> frameDomeEnvironments(const Scene& scene, const RenderSettings& settings,
                                                   Diagnostics& diagnostics) {
    std::vector<DomeEnvironment> domes;
    const DomeLightingMode mode = settings.values().domeLighting;
    if (mode == DomeLightingMode::Ambient) return domes;
    DomeFitSettings fit;
    fit.srbf.maxLobes = settings.values().domeLights;
    for (const auto& [path, entry] : scene.lights()) {
        if (!isDrawnDome(*entry.prim)) continue;
        const glm::vec3 radiance = lightRadiance(*entry.prim);
        domes.push_back(mode == DomeLightingMode::Sampled
                            ? sampledDomeEnvironment(*entry.prim, radiance, settings.values().domeSampledLights,
                                                     diagnostics)
                            : domeEnvironment(*entry.prim, radiance, fit, diagnostics));
    }
    return domes;
}

std::string PlannedDome::describe(size_t lightsPerPass) const {
    if (sampledLights > 0)
        return fmt::format("dome {}: the reference (domeLighting=sampled): {} distant lights importance-sampled from "
                           "its radiance, {} per pass, {}",
                           path, sampledLights, lightsPerPass,
                           shadowedLights > 0 ? "each with a shadow map of its own" : "unshadowed");
    if (srbfLights == 0)
        return fmt::format("dome {}: uniform dome: analytic (no usable texture: the fibre model's exact response to "
                           "uniform radiance, from its SRBF table)",
                           path);
    const std::string shadows =
        shadowedLights == 0 ? std::string("unshadowed")
                            : fmt::format("the {} strongest with a shadow map of their own (domeShadowLights), the "
                                          "rest reading the nearest of those",
                                          shadowedLights);
    return fmt::format("dome {}: {} SRBF lights (fit error {:.3f}), {} per pass, each read from its material's "
                       "SRBF table (domeLighting=srbf); {}",
                       path, srbfLights, fitError, lightsPerPass, shadows);
}

std::vector<PlannedDome> addDomeLights(const Scene& scene, const std::vector<DomeEnvironment>& domes,
                                       int shadowedPerDome, ShadingLights& lights,
                                       std::map<size_t, size_t>& sharedMaps) {
    std::vector<PlannedDome> planned;
    for (const auto& [path, entry] : scene.lights()) {
        const LightPrim& prim = *entry.prim;
        if (!isDrawnDome(prim)) continue;
        // A structured binding cannot be captured in C++17 (clang refuses it).
        const std::string& domePath = path;
        auto found = std::find_if(domes.begin(), domes.end(),
                                  [&](const DomeEnvironment& dome) { return dome.lightPath == domePath; });
        PlannedDome dome;
        dome.path = path;
        dome.firstLight = lights.lights.size();
        lights.uniformDomeCastsShadow = lights.uniformDomeCastsShadow || prim.shadowEnable;
        if (found == domes.end()) {
            lights.uniformDome += lightRadiance(prim);
            planned.push_back(dome);
            continue;
        }
        lights.uniformDome += found->uniformRadiance;
        if (!found->sampledLights.empty()) {
            for (size_t k = 0; k < found->sampledLights.size(); ++k) {
                ShadingLight light;
                light.directionOrPosition = found->sampledLights[k].direction;
                light.scale = found->sampledLights[k].irradiance;
                light.castsShadow = prim.shadowEnable;
                light.path = fmt::format("{} sample {}", path, k);
                lights.lights.push_back(light);
            }
            dome.sampledLights = found->sampledLights.size();
            dome.shadowedLights = prim.shadowEnable ? dome.sampledLights : 0;
            planned.push_back(dome);
            continue;
        }
        dome.fitError = found->fitError;
        const std::vector<Srbf>& srbfs = found->srbfs;
        std::vector<size_t> order(srbfs.size());
        std::iota(order.begin(), order.end(), size_t(0));
        std::stable_sort(order.begin(), order.end(),
                         [&](size_t a, size_t b) { return lobePower(srbfs[a]) > lobePower(srbfs[b]); });
        const size_t shadowed =
            prim.shadowEnable ? std::min(order.size(), size_t(std::max(shadowedPerDome, 0))) : size_t(0);
        for (size_t rank = 0; rank < order.size(); ++rank) {
            const Srbf& srbf = srbfs[order[rank]];
            ShadingLight light;
            light.directionOrPosition = srbf.lobe.centre;
            light.scale = srbf.amplitude;
            light.srbfBandwidth = srbf.lobe.bandwidth;
            light.castsShadow = rank < shadowed;
            light.path = fmt::format("{} srbf {}", path, rank);
            lights.lights.push_back(light);
        }
        // Each unshadowed lobe borrows the map of the shadowed one nearest
        // in direction: the occluders along ξ_j are closest to those along it.
        for (size_t rank = shadowed; rank < order.size() && shadowed > 0; ++rank) {
            const glm::vec3 centre = srbfs[order[rank]].lobe.centre;
            size_t nearest = 0;
            for (size_t other = 1; other < shadowed; ++other)
                if (glm::dot(centre, srbfs[order[other]].lobe.centre) >
                    glm::dot(centre, srbfs[order[nearest]].lobe.centre))
                    nearest = other;
            sharedMaps[dome.firstLight + rank] = dome.firstLight + nearest;
        }
        dome.srbfLights = order.size();
        dome.shadowedLights = shadowed;
        planned.push_back(dome);
    }
    return planned;
}

}  // namespace hdhair
