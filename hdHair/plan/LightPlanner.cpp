#include "hdHair/plan/LightPlanner.h"

#include <algorithm>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "hdHair/plan/CameraView.h"
#include "hdHair/plan/SceneSummary.h"
#include "hdHair/plan/SettingValues.h"
#include "hdHair/scene/Scene.h"

namespace hdhair {

namespace {

// hdHair's camera light, or the host's when it gave one: the host's light
// follows its camera, and is used as it is (its own shadow:enable).
std::vector<ShadingLight> cameraLightsFor(const CameraView& camera, const LightPrim* hostCameraLight,
                                          bool castsShadow) {
    if (hostCameraLight) return toShadingLights({hostCameraLight}).lights;
    return {cameraLightOf(camera, castsShadow)};
}

// Batches of at most `perPass` of the first `count` lights; always at
// least one (ambient and unlit shading need a pass too).
std::vector<std::pair<size_t, size_t>> lightBatches(size_t count, size_t perPass) {
    std::vector<std::pair<size_t, size_t>> batches;
    for (size_t begin = 0; begin < count; begin += perPass) batches.emplace_back(begin, std::min(begin + perPass, count));
    if (batches.empty()) batches.emplace_back(0, 0);
    return batches;
}

// The stage's own lights (at most kMaxLights, in path order), apart from
// the host's camera light and, when domes are lights of their own
// (addDomeLights), the domes.
struct StageLights {
    std::vector<const LightPrim*> lights;
    const LightPrim* hostCameraLight = nullptr;
    size_t overCap = 0;
};

StageLights stageLightsOf(const Scene& scene, bool domesAsLights) {
    StageLights stage;
    for (const auto& [path, entry] : scene.lights()) {
        if (entry.prim->hostCameraLight) {
            if (!stage.hostCameraLight && entry.prim->visible) stage.hostCameraLight = entry.prim.get();
        } else if (domesAsLights && entry.prim->type == LightType::Dome) {
            continue;
        } else if (stage.lights.size() < kMaxLights) {
            stage.lights.push_back(entry.prim.get());
        } else {
            stage.overCap += 1;
        }
    }
    return stage;
}

}  // namespace

ShadingLight cameraLightOf(const CameraView& camera, bool castsShadow) {
    // The camera looks down its -Z: the light comes from +Z of the view.
    const glm::dmat4 cameraToWorld = glm::inverse(camera.view);
    return cameraLight(glm::normalize(glm::vec3(cameraToWorld * glm::dvec4(0.0, 0.0, 1.0, 0.0))), castsShadow);
}

bool usesCameraLight(CameraLightSetting setting, bool stageHasLight, bool anythingLit) {
    return anythingLit &&
           (setting == CameraLightSetting::On || (setting == CameraLightSetting::Auto && !stageHasLight));
}

LightPlan planLights(const Scene& scene, const SettingValues& settings, const CameraView& camera,
                     const StrandSummary& strands, const MeshSummary& meshes,
                     const std::vector<DomeEnvironment>& domes) {
    LightPlan plan;
    // domeLighting=srbf or sampled: domes are SRBF lights and a uniform term,
    // or sampled distant lights (DomeLighting.h), not toShadingLights' flat
    // ambient.
    const bool domesAsLights = settings.domeLighting != DomeLightingMode::Ambient;
    plan.domesSampled = settings.domeLighting == DomeLightingMode::Sampled;
    const StageLights stage = stageLightsOf(scene, domesAsLights);
    plan.overCap = stage.overCap;
    plan.lights = toShadingLights(stage.lights);
    if (domesAsLights)
        plan.domes = addDomeLights(scene, domes, settings.domeShadowLights, plan.lights, plan.sharedMaps);
    // Meshes are lit unless the shadingModel setting asks for flat
    // displayColor (hair prims may still choose their own model).
    plan.meshesLit = meshes.meshes > 0 && settings.shadingModel != ShadingModel::Flat;
    plan.flatShading = !strands.anyLit && !plan.meshesLit;

    const bool stageHasLight = !plan.lights.lights.empty() || glm::length(plan.lights.ambient) > 0.0f ||
                               glm::length(plan.lights.uniformDome) > 0.0f;
    plan.cameraLight = usesCameraLight(settings.cameraLight, stageHasLight, !plan.flatShading);
    if (plan.cameraLight)
        for (const ShadingLight& light :
             cameraLightsFor(camera, stage.hostCameraLight, settings.cameraLightShadows == CameraLightShadows::On))
            plan.lights.lights.push_back(light);
    // Light colours (and colour temperatures) are linear Rec.709, as every
    // authored colour: shading happens in the rendering space.
    plan.renderingSpace = settings.renderingSpace;
    const glm::mat3 toRenderingSpace = rec709To(plan.renderingSpace);
    for (ShadingLight& light : plan.lights.lights) light.scale = toRenderingSpace * light.scale;
    plan.lights.ambient = toRenderingSpace * plan.lights.ambient;
    plan.lights.uniformDome = toRenderingSpace * plan.lights.uniformDome;
    plan.lightsPerPass = size_t(settings.lightsPerPass);
    plan.batches = lightBatches(plan.flatShading ? 0 : plan.lights.lights.size(), plan.lightsPerPass);
    return plan;
}

}  // namespace hdhair
