#include "hdHair/render/RenderPlan.h"

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "hdHair/render/CameraView.h"
#include "hdHair/render/RenderSettings.h"
#include "hdHair/scene/Scene.h"

namespace hdhair {

bool RenderPlan::isEnabled(const std::string& name) const {
    for (const PlannedPass& pass : passes)
        if (pass.name == name) return pass.enabled;
    return false;
}

std::string RenderPlan::describe() const {
    std::string text;
    for (const PlannedPass& pass : passes)
        text += fmt::format("  {:<10} {:<4} {}\n", pass.name, pass.enabled ? "on" : "off", pass.reason);
    return text;
}

nlohmann::json RenderPlan::toJson() const {
    nlohmann::json json = nlohmann::json::array();
    for (const PlannedPass& pass : passes)
        json.push_back({{"pass", pass.name}, {"enabled", pass.enabled}, {"reason", pass.reason}});
    return json;
}

RenderPlan makeRenderPlan(const Scene& scene, const RenderSettings& settings, const CameraView& camera,
                          size_t segmentCount) {
    RenderPlan plan;
    std::vector<const LightPrim*> stageLights;
    const LightPrim* hostCameraLight = nullptr;
    for (const auto& [path, entry] : scene.lights()) {
        if (entry.prim->hostCameraLight) {
            if (!hostCameraLight && entry.prim->visible) hostCameraLight = entry.prim.get();
        } else {
            stageLights.push_back(entry.prim.get());
        }
    }
    plan.lights = toShadingLights(stageLights);

    std::string cameraLight = settings.getToken("cameraLight");
    bool stageHasLight = !plan.lights.lights.empty() || glm::length(plan.lights.ambient) > 0.0f;
    plan.cameraLight = cameraLight == "on" || (cameraLight == "auto" && !stageHasLight);
    if (plan.cameraLight) {
        if (hostCameraLight) {
            // The host's light follows its camera: use it as it is.
            ShadingLights host = toShadingLights({hostCameraLight});
            plan.lights.lights.insert(plan.lights.lights.end(), host.lights.begin(), host.lights.end());
        } else {
            // The camera looks down its -Z: the light comes from +Z of the view.
            glm::dmat4 cameraToWorld = glm::inverse(camera.view);
            glm::vec3 towardsCamera =
                glm::normalize(glm::vec3(cameraToWorld * glm::dvec4(0.0, 0.0, 1.0, 0.0)));
            plan.lights.lights.push_back(hdhair::cameraLight(towardsCamera));
        }
    }

    PlannedPass strands{"strands", segmentCount > 0, ""};
    strands.reason = segmentCount > 0
                         ? fmt::format("{} segments, opaque, depth-tested, Kajiya-Kay, {} light(s){}", segmentCount,
                                       plan.lights.lights.size(), plan.cameraLight ? " incl. the camera light" : "")
                         : "no visible curves: background only";
    plan.passes.push_back(strands);

    PlannedPass meshes{"meshes", false, ""};
    meshes.reason = scene.meshes().empty() ? "no meshes"
                                           : fmt::format("{} mesh(es) kept in the scene; drawing them as occluders "
                                                         "is not implemented yet",
                                                         scene.meshes().size());
    plan.passes.push_back(meshes);
    return plan;
}

}  // namespace hdhair
