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
FramePass idsPass(TransparencyPath path, bool idsRequested, bool anyStrands, bool anyMeshes) {
    FramePass ids{"ids", {"strands", "depth"}, {"ids"}, false, ""};
    if (!idsRequested) {
        ids.reason = "no ids asked for";
    } else if (!anyStrands) {
        ids.reason = anyMeshes ? "no visible curves: the meshes pass writes the ids" : "no visible curves: ids are -1 everywhere";
    } else if (path == TransparencyPath::Opaque) {
        ids.reason = "the strand pass writes them, with depth";
    } else if (path == TransparencyPath::Exact) {
        ids.reason = "the exact resolve writes them, with depth";
    } else {
        ids.wanted = true;
        ids.reason = fmt::format("the host asked for ids: the nearest strand with alpha >= {}, the fragment the "
                                 "strand pass's depth comes from{}",
                                 kNearestStrandMinAlpha, anyMeshes ? ", where it is nearer than the meshes" : "");
    }
    return ids;
}

// What the strand and light-batch passes read: the strands, and the draw
// order when they are bin sorted.
std::vector<FrameResource> strandReads(TransparencyPath path, std::vector<FrameResource> more) {
    std::vector<FrameResource> reads{"strands"};
    if (path == TransparencyPath::BinSorted) reads.push_back("drawOrder");
    reads.insert(reads.end(), more.begin(), more.end());
    return reads;
}

// A later light batch draws what the first drew, with its own lights: the
// strands (when there are any) and the meshes (when there are any).
std::vector<FrameResource> lightBatchReads(TransparencyPath path, bool anyStrands, bool anyMeshes) {
    std::vector<FrameResource> reads = anyStrands ? strandReads(path, {}) : std::vector<FrameResource>{};
    if (anyMeshes) reads.push_back("meshGeometry");
    reads.push_back("color");
    return reads;
}

}  // namespace

void RenderPlan::fallBackToBinSorted(uint32_t bins, bool idsRequested) {
    transparency = TransparencyPath::BinSorted;
    sortBins = bins;
    const bool anyStrands = graph.find("strands")->wanted;
    const bool anyMeshes = graph.find("meshes")->wanted;
    for (FramePass& pass : graph.passes()) {
        if (pass.name == "sort") {
            pass.wanted = true;
            pass.reason = fmt::format("exact fell back: segments into {} depth bins on the CPU", bins);
        } else if (pass.name == "ids") {
            FramePass replacement = idsPass(transparency, idsRequested, anyStrands, anyMeshes);
            pass.wanted = replacement.wanted;
            pass.reason = replacement.reason;
        } else if (pass.name == "strands") {
            std::vector<FrameResource> inPlace(pass.reads.begin() + 1, pass.reads.end());
            inPlace.erase(std::remove(inPlace.begin(), inPlace.end(), "drawOrder"), inPlace.end());
            pass.reads = strandReads(transparency, inPlace);
        } else if (pass.name.rfind("lightBatch", 0) == 0) {
            pass.reads = lightBatchReads(transparency, anyStrands, anyMeshes);
        }
    }
    graph.compile();
}

nlohmann::json RenderPlan::toJson() const { return graph.toJson(); }

RenderPlan makeRenderPlan(const Scene& scene, const RenderSettings& settings, const CameraView& camera,
                          const StrandSummary& strands, bool idsRequested, const MeshSummary& meshes,
                          bool displayOnGpu) {
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
    const bool anyMeshes = meshes.meshes > 0;
    // Meshes are lit unless the shadingModel setting asks for flat
    // displayColor (hair prims may still choose their own model).
    plan.meshesLit = anyMeshes && settings.getToken("shadingModel") != "flat";
    plan.flatShading = !strands.anyLit && !plan.meshesLit;

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

    const bool anyStrands = strands.segments > 0;
    FrameGraph& graph = plan.graph;
    graph.input("preparedStrands");

    FramePass upload{"upload", {"preparedStrands"}, {"strands"}, anyStrands, ""};
    upload.reason = anyStrands ? fmt::format("{} segments to the GPU: only prims that changed since the last frame",
                                             strands.segments)
                               : "no visible curves";
    graph.add(upload);

    graph.input("preparedMeshes");
    // Why the mesh passes are off, when they are.
    const std::string noMeshes = scene.meshes().empty() ? "no meshes" : "no visible meshes";
    FramePass meshUpload{"meshUpload", {"preparedMeshes"}, {"meshGeometry"}, anyMeshes, ""};
    meshUpload.reason = !anyMeshes       ? noMeshes
                        : meshes.changed ? fmt::format("{} mesh(es), {} triangles to the GPU: a mesh changed since the "
                                                       "last frame",
                                                       meshes.meshes, meshes.triangles)
                                         : "the meshes on the GPU are current: nothing to send";
    graph.add(meshUpload);

    FramePass sort{"sort", {"preparedStrands"}, {"drawOrder"},
                   plan.transparency == TransparencyPath::BinSorted && anyStrands, ""};
    sort.reason = sort.wanted ? fmt::format("{} segments into {} depth bins on the CPU, O(n)", strands.segments,
                                            plan.sortBins)
                              : "no bin sorting on this path";
    graph.add(sort);

    std::vector<FrameResource> frameImages{"color", "depth"};
    if (idsRequested) frameImages.push_back("ids");
    graph.add(FramePass{"clear", {}, frameImages, true, "the frame's images, empty (transparent black, depth 1, ids -1)"});

    std::vector<FrameResource> meshReads{"meshGeometry"};
    meshReads.insert(meshReads.end(), frameImages.begin(), frameImages.end());
    FramePass meshPass{"meshes", meshReads, frameImages, anyMeshes, ""};
    if (anyMeshes) {
        const std::string levels = meshes.minRefineLevel == meshes.maxRefineLevel
                                       ? fmt::format("refine level {}", meshes.minRefineLevel)
                                       : fmt::format("refine levels {}-{}", meshes.minRefineLevel,
                                                     meshes.maxRefineLevel);
        meshPass.reason = fmt::format("{} mesh(es), {} triangles ({}), opaque, {}; drawn before the strands: depth "
                                      "{}written, strands behind them hidden",
                                      meshes.meshes, meshes.triangles, levels,
                                      plan.meshesLit ? "Lambert under the lights" : "flat displayColor",
                                      idsRequested ? "and ids " : "");
    } else {
        meshPass.reason = noMeshes;
    }
    graph.add(meshPass);

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
    // The strand pass writes ids itself where it can keep the nearest
    // fragment's (opaque, and exact's resolve).
    std::vector<FrameResource> strandWrites{"color", "depth"};
    if (idsRequested && (plan.transparency == TransparencyPath::Opaque || plan.transparency == TransparencyPath::Exact))
        strandWrites.push_back("ids");
    std::vector<FrameResource> inPlace = strandWrites;
    FramePass strandPass{"strands", strandReads(plan.transparency, inPlace), strandWrites, anyStrands, ""};
    strandPass.reason = anyStrands ? fmt::format("{} segments, {}: {}{}, {}; {}", strands.segments,
                                                 toString(plan.transparency), why, multisampling, shading,
                                                 depthSource(plan.transparency))
                                   : "no visible curves: background only";
    graph.add(strandPass);

    graph.add(idsPass(plan.transparency, idsRequested, anyStrands, anyMeshes));

    // Light batches add onto the frame's resolved colour, and readback reads
    // it: a multisampled frame is resolved once, here.
    FramePass resolve{"resolve", frameImages, frameImages, plan.msaaSamples > 0, ""};
    resolve.reason = resolve.wanted ? fmt::format("{} samples a pixel averaged (depth and ids: one sample)",
                                                  plan.msaaSamples)
                                    : "no multisampling";
    graph.add(resolve);

    size_t perPass = size_t(settings.getInt("lightsPerPass"));
    size_t lightCount = plan.flatShading ? 0 : plan.lights.lights.size();
    for (size_t begin = 0; begin < lightCount; begin += perPass)
        plan.lightBatches.emplace_back(begin, std::min(begin + perPass, lightCount));
    if (plan.lightBatches.empty()) plan.lightBatches.emplace_back(0, 0);
    const std::string drawnAgain = anyStrands && anyMeshes ? "the meshes and the strands"
                                   : anyMeshes                ? "the meshes"
                                                              : "the strands";
    for (size_t batch = 1; batch < plan.lightBatches.size(); ++batch) {
        FramePass lights{fmt::format("lightBatch {}", batch + 1),
                         lightBatchReads(plan.transparency, anyStrands, anyMeshes), {"color"},
                         anyStrands || anyMeshes, ""};
        lights.reason = fmt::format("lights {}-{} of {} (lightsPerPass {}): {} again, colour added, alpha "
                                    "counted once",
                                    plan.lightBatches[batch].first + 1, plan.lightBatches[batch].second, lightCount,
                                    perPass, drawnAgain);
        graph.add(lights);
    }

    graph.add(FramePass{"readback", frameImages, {"aovs"}, true, "the frame's images to the CPU"});
    graph.output("aovs");
    graph.add(FramePass{"displayTransform", {"color"}, {"displayImage"}, displayOnGpu,
                        displayOnGpu ? "the display image through the display transform's GLSL, on the GPU"
                                     : "no display image asked of the GPU (display transforms run on the CPU)"});
    if (displayOnGpu) graph.output("displayImage");
    graph.compile();
    return plan;
}

}  // namespace hdhair
