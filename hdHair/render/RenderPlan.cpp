#include "hdHair/render/RenderPlan.h"

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "hdHair/render/CameraView.h"
#include "hdHair/render/NearestStrandRule.h"
#include "hdHair/render/RenderSettings.h"
#include "hdHair/scene/Scene.h"

namespace hdhair {

const char* toString(TransparencyPath path) {
    switch (path) {
    case TransparencyPath::Opaque: return "opaque";
    case TransparencyPath::BinSorted: return "binSorted";
    case TransparencyPath::Exact: return "exact";
    case TransparencyPath::Unsorted: return "unsorted";
    }
    return "opaque";
}

namespace {

// Where the frame's depth comes from on each path (and, blended, its ids).
std::string depthSource(TransparencyPath path) {
    switch (path) {
    case TransparencyPath::Opaque: return "depth: the depth buffer";
    case TransparencyPath::Exact:
        return fmt::format("depth and ids: the nearest listed fragment with alpha >= {}", kNearestStrandMinAlpha);
    case TransparencyPath::BinSorted:
    case TransparencyPath::Unsorted: break;
    }
    return fmt::format("depth: the nearest fragment with alpha >= {}, min-blended", kNearestStrandMinAlpha);
}

// Ids need a pass of their own only where blending draws strands in an
// order that is not nearest-last (integer images cannot be min-blended).
PlannedPass idsPass(TransparencyPath path, bool idsRequested, bool anyStrands) {
    PlannedPass ids{"ids", false, ""};
    if (!idsRequested) {
        ids.reason = "no ids asked for";
    } else if (!anyStrands) {
        ids.reason = "no visible curves: ids are -1 everywhere";
    } else if (path == TransparencyPath::Opaque) {
        ids.reason = "the strand pass writes them, with depth";
    } else if (path == TransparencyPath::Exact) {
        ids.reason = "the exact resolve writes them, with depth";
    } else {
        ids.enabled = true;
        ids.reason = fmt::format("the host asked for ids: the nearest strand with alpha >= {}, the fragment the "
                                 "strand pass's depth comes from",
                                 kNearestStrandMinAlpha);
    }
    return ids;
}

}  // namespace

bool RenderPlan::isEnabled(const std::string& name) const {
    for (const PlannedPass& pass : passes)
        if (pass.name == name) return pass.enabled;
    return false;
}

void RenderPlan::fallBackToBinSorted(uint32_t bins, bool idsRequested) {
    transparency = TransparencyPath::BinSorted;
    sortBins = bins;
    const bool anyStrands = isEnabled("strands");
    for (PlannedPass& pass : passes) {
        if (pass.name == "sort") {
            pass.enabled = true;
            pass.reason = fmt::format("exact fell back: segments into {} depth bins on the CPU", bins);
        } else if (pass.name == "ids") {
            pass = idsPass(transparency, idsRequested, anyStrands);
        }
    }
}

std::string RenderPlan::describe() const {
    std::string text;
    for (const PlannedPass& pass : passes)
        text += fmt::format("  {:<12} {:<4} {}\n", pass.name, pass.enabled ? "on" : "off", pass.reason);
    return text;
}

nlohmann::json RenderPlan::toJson() const {
    nlohmann::json json = nlohmann::json::array();
    for (const PlannedPass& pass : passes)
        json.push_back({{"pass", pass.name}, {"enabled", pass.enabled}, {"reason", pass.reason}});
    return json;
}

RenderPlan makeRenderPlan(const Scene& scene, const RenderSettings& settings, const CameraView& camera,
                          const StrandSummary& strands, bool idsRequested) {
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
    plan.flatShading = !strands.anyLit;

    std::string cameraLight = settings.getToken("cameraLight");
    bool stageHasLight = !plan.lights.lights.empty() || glm::length(plan.lights.ambient) > 0.0f;
    plan.cameraLight = !plan.flatShading && (cameraLight == "on" || (cameraLight == "auto" && !stageHasLight));
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

    // Transparency: what was asked for, unless the stage does not need it.
    std::string requested = settings.getToken("transparency");
    double threshold = settings.getFloat("minPixelWidth");
    bool needsBlending = !strands.allOpaque || strands.minProjectedWidthPixels < threshold;
    std::string why;
    if (requested == "opaque") {
        plan.transparency = TransparencyPath::Opaque;
        why = "transparency=opaque: opacity and sub-pixel coverage ignored";
    } else if (!needsBlending) {
        plan.transparency = TransparencyPath::Opaque;
        why = fmt::format("every strand is opaque and at least {:.2f} px wide (>= minPixelWidth {}): no blending "
                          "or sorting needed",
                          strands.minProjectedWidthPixels, threshold);
    } else if (requested == "exact") {
        plan.transparency = TransparencyPath::Exact;
        why = "per-pixel fragment lists sorted by depth (exact)";
    } else if (requested == "unsorted") {
        plan.transparency = TransparencyPath::Unsorted;
        why = "pre-multiplied blending in authored order, unsorted";
    } else {
        plan.transparency = TransparencyPath::BinSorted;
        plan.sortBins = uint32_t(settings.getInt("sortBins"));
        why = fmt::format("{} bins, drawn far to near with pre-multiplied blending", plan.sortBins);
    }
    if (plan.transparency != TransparencyPath::Opaque)
        why += fmt::format(" ({}; thinnest strand {:.2f} px)", strands.allOpaque ? "opaque strands" : "translucent strands",
                           strands.minProjectedWidthPixels);
    if (plan.transparency == TransparencyPath::Opaque) plan.msaaSamples = settings.getInt("msaaSamples");

    PlannedPass sort{"sort", plan.transparency == TransparencyPath::BinSorted && strands.segments > 0, ""};
    sort.reason = sort.enabled ? fmt::format("{} segments into {} depth bins on the CPU, O(n)", strands.segments,
                                             plan.sortBins)
                               : "no bin sorting on this path";
    plan.passes.push_back(sort);

    PlannedPass strandPass{"strands", strands.segments > 0, ""};
    std::string models = strands.shadingModels.empty() ? std::string("kajiyaKay") : strands.shadingModels;
    if (strands.perPointPrims > 0)
        models += fmt::format(" (per-curve/vertex parameters on {} prim(s))", strands.perPointPrims);
    if (strands.analyticPrims > 0)
        models += fmt::format(" (Marschner azimuthal terms per fragment on {} prim(s))", strands.analyticPrims);
    std::string shading = plan.flatShading ? "flat displayColor"
                                           : fmt::format("{}, {} light(s){}", models, plan.lights.lights.size(),
                                                         plan.cameraLight ? " incl. the camera light" : "");
    std::string multisampling =
        plan.msaaSamples > 0 ? fmt::format(", {}x MSAA", plan.msaaSamples) : std::string();
    strandPass.reason = strands.segments > 0
                            ? fmt::format("{} segments, {}: {}{}, {}; {}", strands.segments,
                                          toString(plan.transparency), why, multisampling, shading,
                                          depthSource(plan.transparency))
                            : "no visible curves: background only";
    plan.passes.push_back(strandPass);

    size_t perPass = size_t(settings.getInt("lightsPerPass"));
    size_t lightCount = plan.flatShading ? 0 : plan.lights.lights.size();
    for (size_t begin = 0; begin < lightCount; begin += perPass)
        plan.lightBatches.emplace_back(begin, std::min(begin + perPass, lightCount));
    if (plan.lightBatches.empty()) plan.lightBatches.emplace_back(0, 0);
    PlannedPass batches{"lightBatches", plan.lightBatches.size() > 1 && strands.segments > 0, ""};
    batches.reason = batches.enabled
                         ? fmt::format("{} lights in {} passes of at most {} (lightsPerPass), each over the same "
                                       "strands: colours summed, alpha counted once",
                                       lightCount, plan.lightBatches.size(), perPass)
                         : fmt::format("{} light(s): one pass", lightCount);
    plan.passes.push_back(batches);

    plan.passes.push_back(idsPass(plan.transparency, idsRequested, strands.segments > 0));

    PlannedPass meshes{"meshes", false, ""};
    meshes.reason = scene.meshes().empty() ? "no meshes"
                                           : fmt::format("{} mesh(es) kept in the scene; drawing them as occluders "
                                                         "is not implemented yet",
                                                         scene.meshes().size());
    plan.passes.push_back(meshes);
    return plan;
}

}  // namespace hdhair
