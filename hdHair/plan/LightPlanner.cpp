#include "hdHair/plan/LightPlanner.h"

#include <algorithm>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "hdHair/plan/CameraView.h"
#include "hdHair/plan/FrameRecipe.h"
#include "hdHair/plan/RenderSettings.h"
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

void planLights(FrameRecipe& recipe, const Scene& scene, const RenderSettings& settings, const CameraView& camera,
                const StrandSummary& strands, const MeshSummary& meshes, const std::vector<DomeEnvironment>& domes) {
    const SettingValues& values = settings.values();
    // domeLighting=srbf or sampled: domes are SRBF lights and a uniform term,
    // or sampled distant lights (DomeLighting.h), not toShadingLights' flat
    // ambient.
    const bool domesAsLights = values.domeLighting != DomeLightingMode::Ambient;
    std::vector<const LightPrim*> stageLights;
    const LightPrim* hostCameraLight = nullptr;
    for (const auto& [path, entry] : scene.lights()) {
        if (entry.prim->hostCameraLight) {
            if (!hostCameraLight && entry.prim->visible) hostCameraLight = entry.prim.get();
        } else if (domesAsLights && entry.prim->type == LightType::Dome) {
            continue;  // addDomeLights below
        } else if (stageLights.size() < kMaxLights) {
            stageLights.push_back(entry.prim.get());
        } else {
            recipe.lightsOverCap += 1;
        }
    }
    recipe.lights = toShadingLights(stageLights);
    if (domesAsLights)
        recipe.domes = addDomeLights(scene, domes, values.domeShadowLights, recipe.lights, recipe.shadows.sharedMaps);
    // Meshes are lit unless the shadingModel setting asks for flat
    // displayColor (hair prims may still choose their own model).
    recipe.meshesLit = meshes.meshes > 0 && values.shadingModel != ShadingModel::Flat;
    recipe.flatShading = !strands.anyLit && !recipe.meshesLit;

    const bool stageHasLight = !recipe.lights.lights.empty() || glm::length(recipe.lights.ambient) > 0.0f ||
                               glm::length(recipe.lights.uniformDome) > 0.0f;
    recipe.cameraLight = usesCameraLight(values.cameraLight, stageHasLight, !recipe.flatShading);
    if (recipe.cameraLight)
        for (const ShadingLight& light :
             cameraLightsFor(camera, hostCameraLight, values.cameraLightShadows == CameraLightShadows::On))
            recipe.lights.lights.push_back(light);
    // Light colours (and colour temperatures) are linear Rec.709, as every
    // authored colour: shading happens in the rendering space.
    const glm::mat3 toRenderingSpace = rec709To(settings.renderingSpace());
    for (ShadingLight& light : recipe.lights.lights) light.scale = toRenderingSpace * light.scale;
    recipe.lights.ambient = toRenderingSpace * recipe.lights.ambient;
    recipe.lights.uniformDome = toRenderingSpace * recipe.lights.uniformDome;
    recipe.lightBatches =
        lightBatches(recipe.flatShading ? 0 : recipe.lights.lights.size(), size_t(values.lightsPerPass));
}

}  // namespace hdhair
