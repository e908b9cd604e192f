#include "hdHair/plan/RenderPlan.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "hdHair/plan/NearestStrandRule.h"
#include "hdHair/plan/RenderSettings.h"
#include "hdHair/scene/Scene.h"

namespace hdhair {

namespace {

// Where the frame's depth comes from on each path (and, blended, its ids).
std::string depthSource(const FrameRecipe& recipe) {
    if (recipe.transparency.path == TransparencyPath::Opaque) return "depth: the depth buffer";
    if (recipe.compositesFromLists())
        return fmt::format("depth and ids: the nearest listed fragment with alpha >= {}", kNearestStrandMinAlpha);
    return fmt::format("depth: the nearest fragment with alpha >= {}, min-blended", kNearestStrandMinAlpha);
}

// Ids need a pass of their own only where blending draws strands in an
// order that is not nearest-last (integer images cannot be min-blended).
FramePass idsPass(const FrameRecipe& recipe, bool idsRequested, bool anyStrands, bool anyMeshes) {
    FramePass ids{PassKind::Ids, "ids", {ResourceKind::Strands, ResourceKind::Depth}, {ResourceKind::Ids}, false, ""};
    if (!idsRequested) {
        ids.reason = "no ids asked for";
    } else if (!anyStrands) {
        ids.reason = anyMeshes ? "no visible curves: the meshes pass writes the ids" : "no visible curves: ids are -1 everywhere";
    } else if (recipe.transparency.path == TransparencyPath::Opaque) {
        ids.reason = "the strand pass writes them, with depth";
    } else if (recipe.compositesFromLists()) {
        ids.reason = "the fragment lists' resolve writes them, with depth";
    } else {
        ids.wanted = true;
        ids.reason = fmt::format("the host asked for ids: the nearest strand with alpha >= {}, the fragment the "
                                 "strand pass's depth comes from{}",
                                 kNearestStrandMinAlpha, anyMeshes ? ", where it is nearer than the meshes" : "");
    }
    return ids;
}

// What the strand and light-batch passes read: the strands, and the draw
// order when they are drawn bin sorted.
std::vector<FrameResource> strandReads(const FrameRecipe& recipe, std::vector<FrameResource> more) {
    std::vector<FrameResource> reads{ResourceKind::Strands};
    if (recipe.drawsSorted()) reads.push_back(ResourceKind::DrawOrder);
    reads.insert(reads.end(), more.begin(), more.end());
    return reads;
}

// The renderer's decision for a map (ShadowMapAssignment) on a pass that
// would build it: rebuilt says why; kept, or no map, and the pass does not run.
void applyMapDecision(FramePass& pass, const PlannedShadow& shadow) {
    if (!shadow.assigned || !pass.wanted) return;
    if (shadow.slot >= 0 && shadow.rebuild) {
        pass.reason = shadow.reason + "; " + pass.reason;
        return;
    }
    pass.wanted = false;
    pass.reason = shadow.reason;
}

// Whether the renderer gave `shadow` no map (its lookups read none).
bool assignedNoMap(const PlannedShadow& shadow) { return shadow.assigned && shadow.slot < 0; }

// What "meshShadow L" draws, and from where.
std::string meshViewDescription(const PlannedShadow& shadow, int resolution) {
    const ShadowLightView& view = shadow.meshView;
    return fmt::format("{} light view of the hair and meshes, {}x{}: the nearest mesh per texel, opaque: the hair "
                       "and the meshes behind it are unlit{}",
                       view.orthographic ? "orthographic" : "perspective", resolution, resolution,
                       shadow.meshFallback.empty() ? "" : " (" + shadow.meshFallback + ")");
}

// "meshShadow L", drawn with or without hair: meshes shadow each other.
FramePass meshShadowPass(const ShadowPlan& shadows, size_t index, const std::string& flat) {
    const PlannedShadow& shadow = shadows.lights[index];
    const bool wanted = shadow.meshView.valid;
    return FramePass{PassKind::MeshShadow, "meshShadow " + shadow.key, {ResourceKind::MeshGeometry},
                     {shadows.meshResourceOf(index)}, wanted,
                     (wanted              ? meshViewDescription(shadow, shadows.resolution)
                      : shadow.overBudget ? "no shadows from this light: " + shadow.view.fallback
                                          : shadow.meshFallback) +
                         flat};
}

// The passes that build light `shadow`'s map, wanted or not with the reason.
void addShadowPasses(FrameGraph& graph, const FrameRecipe& recipe, size_t index, bool anyStrands) {
    const ShadowPlan& shadows = recipe.shadows;
    const PlannedShadow& shadow = shadows.lights[index];
    auto add = [&](FramePass pass) {
        applyMapDecision(pass, shadow);
        graph.add(std::move(pass)).subject = index;
    };
    // A map kept from an earlier frame comes into the graph from outside.
    if (shadow.assigned && shadow.slot >= 0 && !shadow.rebuild) {
        graph.input(shadows.resourceOf(index));
        if (shadows.meshesCast) graph.input(shadows.meshResourceOf(index));
    }
    bool wanted = false;
    std::string why, flat;
    if (shadows.mode == ShadowMode::Off) {
        why = "shadowMode=off";
    } else if (!anyStrands) {
        why = "no visible curves";
    } else if (shadow.byVolume) {
        why = "no map: " + shadow.volumeReason;
    } else if (!shadow.view.valid) {
        why = "no shadows from this light: " + shadow.view.fallback;
    } else {
        wanted = true;
        why = fmt::format("{} light view, {}x{}", shadow.view.orthographic ? "orthographic" : "perspective",
                          shadows.resolution, shadows.resolution);
        if (recipe.lighting.flatShading) flat = "; every prim is flat-shaded, so no pass reads lights or their shadows";
    }
    const std::string& key = shadow.key;
    if (shadows.mode == ShadowMode::Reference) {
        add(FramePass{PassKind::ShadowFragments, "shadowFragments " + key, {ResourceKind::Strands}, {{ResourceKind::ShadowFragments, index}}, wanted,
                            why + (wanted ? ": every fragment kept per texel, the reference (slow)" : "") + flat});
    } else {
        // How the strands are drawn there, when they are.
        const std::string drawn =
            !wanted ? ""
            : shadow.strandLines
                ? fmt::format("; strands as one-texel lines (the widest is {:.2f} texels){}", shadow.widestTexels,
                              shadow.computeLines    ? ", " + shadow.rasterReason
                              : shadow.straightSpans ? ", spans of one segment without the tessellator, " +
                                                           shadow.rasterReason
                                                   : ", every span through the tessellator (shadowStrandLines=tessellated)")
                : fmt::format("; strands as ribbons ({})",
                              shadow.widestTexels > kMaxStrandLineTexels
                                  ? fmt::format("the widest is {:.2f} texels", shadow.widestTexels)
                              : shadows.minPixelWidth > 1.0 ? "minPixelWidth above 1"
                                                            : "shadowStrandLines=off");
        add(FramePass{PassKind::ShadowDepth, "shadowDepth " + key, {ResourceKind::Strands}, {{ResourceKind::HairDepth, index}}, wanted,
                            why + (wanted ? ": the nearest hair per texel" : "") + drawn + flat});
        add(FramePass{PassKind::DeepOpacity, "deepOpacity " + key, {ResourceKind::Strands, {ResourceKind::HairDepth, index}}, {{ResourceKind::DeepOpacity, index}}, wanted,
                            (wanted ? why + fmt::format(": {} opacity layers behind it, the last {} of the hair's "
                                                        "depth along the light",
                                                        shadows.layers, shadows.layerDepth)
                                    : why) +
                                drawn + flat});
    }
    if (shadows.meshesCast) add(meshShadowPass(shadows, index, flat));
}

// The opacity layers of every map averaged into a mip chain ("opacityMipmaps").
const FrameResource kConvolvedOpacity{ResourceKind::ConvolvedOpacity};

// The shadow maps light batch `batch` reads: those of its lights that have
// one, and the mip chain when its SRBF lights read through it.
std::vector<FrameResource> batchShadowReads(const FrameRecipe& recipe, size_t batch) {
    std::vector<FrameResource> reads;
    if (recipe.shadows.mode == ShadowMode::Off) return reads;
    bool srbfMapRead = false;
    auto readOnce = [&reads](FrameResource map) {
        // SRBF lights share maps (ShadowPlan::sharedMaps): each read once.
        if (std::find(reads.begin(), reads.end(), map) == reads.end()) reads.push_back(map);
    };
    for (size_t light = recipe.lighting.batches[batch].first; light < recipe.lighting.batches[batch].second; ++light) {
        const int shadow = recipe.shadows.shadowOf(light);
        if (shadow < 0 || assignedNoMap(recipe.shadows.lights[size_t(shadow)])) continue;
        const PlannedShadow& planned = recipe.shadows.lights[size_t(shadow)];
        if (recipe.shadows.meshesCast && planned.meshView.valid) readOnce(recipe.shadows.meshResourceOf(size_t(shadow)));
        if (planned.byVolume && recipe.shadows.usesVolume()) readOnce(ResourceKind::DensityVolume);
        if (!planned.view.valid) continue;
        srbfMapRead = srbfMapRead || recipe.lighting.lights.lights[light].isSrbf();
        readOnce(recipe.shadows.resourceOf(size_t(shadow)));
    }
    // Its SRBF lights that read a map read it through the mip chain (which
    // "opacityMipmaps" makes whenever an SRBF light has a map).
    if (recipe.shadows.convolvedOpacity && srbfMapRead) reads.push_back(kConvolvedOpacity);
    // Dual scattering's local term reads the volume under every light; the
    // uniform dome belongs to the first batch (lightUniforms).
    const bool volumeRead = recipe.shadows.volumeBackScattering || (batch == 0 && recipe.shadows.volumeDomeOcclusion);
    if (volumeRead && recipe.shadows.usesVolume()) readOnce(ResourceKind::DensityVolume);
    return reads;
}

// upload, meshUpload and sort: the CPU's strands and meshes to the GPU,
// and the bin sort's draw order.
void addUploadPasses(FrameGraph& graph, const FrameRecipe& recipe, const StrandSummary& strands,
                     const MeshSummary& meshes, const std::string& noMeshes) {
    const bool anyStrands = strands.segments > 0, anyMeshes = meshes.meshes > 0;
    graph.input(ResourceKind::PreparedStrands);
    graph.add(FramePass{PassKind::Upload, "upload", {ResourceKind::PreparedStrands}, {ResourceKind::Strands}, anyStrands,
                        anyStrands ? fmt::format("{} segments to the GPU: only prims that changed since the last frame",
                                                 strands.segments)
                                   : "no visible curves"});
    graph.input(ResourceKind::PreparedMeshes);
    graph.add(FramePass{PassKind::MeshUpload, "meshUpload", {ResourceKind::PreparedMeshes}, {ResourceKind::MeshGeometry}, anyMeshes,
                        !anyMeshes       ? noMeshes
                        : meshes.changed ? fmt::format("{} mesh(es), {} triangles to the GPU: a mesh changed since "
                                                       "the last frame",
                                                       meshes.meshes, meshes.triangles)
                                         : "the meshes on the GPU are current: nothing to send"});
    const bool sorted = recipe.drawsSorted() && anyStrands;
    graph.add(FramePass{PassKind::Sort,
                        "sort",
                        {ResourceKind::PreparedStrands},
                        {ResourceKind::DrawOrder},
                        sorted,
                        sorted ? fmt::format("{} segments into {} depth bins on the CPU, O(n)", strands.segments,
                                             recipe.transparency.sortBins)
                        : recipe.strandRaster.rasteriser == StrandRaster::Compute
                            ? "no bin sorting: the compute rasteriser's lists are sorted per pixel"
                            : "no bin sorting on this path"});
}

// "densityVolume": the hair's optical density on a grid, for the lights
// shadowed through it.
void addDensityVolumePass(FrameGraph& graph, const FrameRecipe& recipe, bool anyStrands) {
    const ShadowPlan& shadows = recipe.shadows;
    std::vector<std::string> lights;
    for (const PlannedShadow& shadow : shadows.lights)
        if (shadow.byVolume) lights.push_back(shadow.key + ": " + shadow.volumeReason);
    if (shadows.volumeBackScattering) lights.push_back("dual scattering's " + shadows.backScatteringReason);
    if (shadows.volumeDomeOcclusion) lights.push_back(shadows.domeOcclusionReason);
    const bool wanted = anyStrands && shadows.usesVolume();
    const DensityGridShape& grid = shadows.volumeGrid;
    graph.add(FramePass{
        PassKind::DensityVolume, "densityVolume", {ResourceKind::PreparedStrands}, {ResourceKind::DensityVolume},
        wanted,
        wanted ? fmt::format("the hair's optical density on {}x{}x{} voxels of {:.3g} ({:.1f} MB{}), for {}",
                             grid.dims.x, grid.dims.y, grid.dims.z, grid.voxelSize,
                             double(grid.voxelCount()) * 4.0 / (1024.0 * 1024.0),
                             shadows.volumeCoarsened ? "; " + shadows.volumeNote : "", fmt::join(lights, "; "))
        : !anyStrands ? "no visible curves"
                      : fmt::format("no light is shadowed through it (shadowMode={}), nor the uniform dome, and "
                                    "dual scattering does not read it",
                                    toString(shadows.setting))});
}

// Every shadow map's passes, the density volume, then the mip chain that
// averages the maps when an SRBF light reads through it.
void addShadowMapPasses(FrameGraph& graph, const FrameRecipe& recipe, bool anyStrands) {
    for (size_t shadow = 0; shadow < recipe.shadows.lights.size(); ++shadow)
        addShadowPasses(graph, recipe, shadow, anyStrands);
    addDensityVolumePass(graph, recipe, anyStrands);
    if (!recipe.shadows.convolvedOpacity) return;
    // After every map it averages: the chain covers the whole array.
    // Wanted exactly when a batch reads the chain: an SRBF light has a
    // map (batchShadowReads); no strands, no valid light views.
    FramePass mipmaps{PassKind::OpacityMipmaps, "opacityMipmaps", {}, {kConvolvedOpacity}, true, ""};
    size_t lobes = 0;
    for (size_t index = 0; index < recipe.shadows.lights.size(); ++index) {
        const PlannedShadow& shadow = recipe.shadows.lights[index];
        if (!shadow.view.valid || assignedNoMap(shadow)) continue;
        mipmaps.reads.push_back(recipe.shadows.resourceOf(index));
        lobes += recipe.lighting.lights.lights[shadow.light].isSrbf() ? 1 : 0;
    }
    mipmaps.wanted = lobes > 0;
    mipmaps.reason = mipmaps.wanted ? fmt::format("the opacity layers of {} SRBF light map(s) averaged into a mip "
                                                  "chain: the convolution optical depth map their lookups widen "
                                                  "over with depth (domeShadowFilter=mipmap; Ren et al. 2010 §5)",
                                                  lobes)
                                    : "no SRBF light has a map";
    graph.add(mipmaps);
}

// The meshes pass: opaque, before the strands, with the lights of batch 1.
FramePass meshesPass(const std::vector<FrameResource>& frameImages, const FrameRecipe& recipe,
                     const MeshSummary& meshes, bool idsRequested, const std::string& noMeshes) {
    std::vector<FrameResource> reads{ResourceKind::MeshGeometry};
    reads.insert(reads.end(), frameImages.begin(), frameImages.end());
    // Lit, they read the first batch's shadows: the hair's and the meshes'.
    if (recipe.lighting.meshesLit && !recipe.lighting.batches.empty())
        for (const FrameResource& map : batchShadowReads(recipe, 0))
            if (map.kind == ResourceKind::DeepOpacity || map.kind == ResourceKind::ShadowFragments ||
                map.kind == ResourceKind::MeshDepth || map.kind == ResourceKind::DensityVolume)
                reads.push_back(map);
    FramePass pass{PassKind::Meshes, "meshes", reads, frameImages, meshes.meshes > 0, noMeshes};
    if (!pass.wanted) return pass;
    const std::string levels = meshes.minRefineLevel == meshes.maxRefineLevel
                                   ? fmt::format("refine level {}", meshes.minRefineLevel)
                                   : fmt::format("refine levels {}-{}", meshes.minRefineLevel, meshes.maxRefineLevel);
    pass.reason = fmt::format(
        "{} mesh(es), {} triangles ({}), opaque, {}; drawn before the strands: depth "
        "{}written, strands behind them hidden",
        meshes.meshes, meshes.triangles, levels,
        recipe.lighting.meshesLit ? "Lambert under the lights" : "flat displayColor", idsRequested ? "and ids " : "");
    return pass;
}

// How the strands are shaded, for the strand pass's reason.
std::string shadingDescription(const FrameRecipe& recipe, const StrandSummary& strands) {
    if (recipe.lighting.flatShading) return "flat displayColor";
    std::string models = strands.shadingModels.empty() ? std::string("kajiyaKay") : strands.shadingModels;
    if (strands.perPointPrims > 0)
        models += fmt::format(" (per-curve/vertex parameters on {} prim(s))", strands.perPointPrims);
    if (strands.analyticPrims > 0)
        models += fmt::format(" (Marschner azimuthal terms per fragment on {} prim(s))", strands.analyticPrims);
    // The camera light, when used, is the last light.
    const std::string cameraLight = !recipe.lighting.cameraLight || recipe.lighting.lights.lights.empty() ? ""
                                    : recipe.lighting.lights.lights.back().castsShadow
                                        ? " incl. the camera light"
                                        : " incl. the camera light, which casts no shadow (cameraLightShadows)";
    std::string shading = fmt::format("{}, {} light(s){}", models, recipe.lighting.lights.lights.size(), cameraLight);
    for (const PlannedDome& dome : recipe.lighting.domes)
        shading += "; " + dome.describe(recipe.lighting.lightsPerPass);
    if (!recipe.shadows.sampling.empty()) shading += "; " + recipe.shadows.sampling;
    for (const std::string& material : strands.multipleScattering) shading += "; multiple scattering on " + material;
    if (strands.dualScatteringMaterials > 0 && recipe.shadows.mode == ShadowMode::Off)
        shading += " (shadowMode=off: every light reaches every fibre, so only the local back scattering adds)";
    if (!recipe.shadows.backScatteringReason.empty()) shading += "; " + recipe.shadows.backScatteringReason;
    if (!recipe.shadows.domeOcclusionReason.empty()) shading += "; " + recipe.shadows.domeOcclusionReason;
    return shading;
}

// The strand pass: the strands with the lights of batch 1 and their shadows.
FramePass strandsPass(const FrameRecipe& recipe, const StrandSummary& strands, bool idsRequested) {
    // The strand pass writes ids itself where it can keep the nearest
    // fragment's (opaque, and exact's resolve).
    std::vector<FrameResource> writes{ResourceKind::Color, ResourceKind::Depth};
    if (idsRequested && (recipe.transparency.path == TransparencyPath::Opaque || recipe.compositesFromLists()))
        writes.push_back(ResourceKind::Ids);
    std::vector<FrameResource> inPlace = writes;
    for (const FrameResource& shadow : batchShadowReads(recipe, 0)) inPlace.push_back(shadow);
    const bool anyStrands = strands.segments > 0;
    const std::string multisampling = recipe.transparency.msaaSamples > 0
                                          ? fmt::format(", {}x MSAA", recipe.transparency.msaaSamples)
                                          : std::string();
    return FramePass{
        PassKind::Strands,
        "strands",
        strandReads(recipe, inPlace),
        writes,
        anyStrands,
        anyStrands ? fmt::format("{} segments, {}: {}{}; {}; {}; {}", strands.segments,
                                 toString(recipe.transparency.path), recipe.transparency.reason, multisampling,
                                 recipe.strandRaster.reason, shadingDescription(recipe, strands), depthSource(recipe))
                   : "no visible curves: background only"};
}

// "lightBatch k" for every batch after the first: what the first drew,
// again, with its own lights and their shadows.
void addLightBatchPasses(FrameGraph& graph, const FrameRecipe& recipe, bool anyStrands, bool anyMeshes) {
    const std::string drawnAgain = anyStrands && anyMeshes ? "the meshes and the strands"
                                   : anyMeshes                ? "the meshes"
                                                              : "the strands";
    const size_t lightCount = recipe.lighting.batches.back().second;
    for (size_t batch = 1; batch < recipe.lighting.batches.size(); ++batch) {
        std::vector<FrameResource> reads;
        if (anyMeshes) reads.push_back(ResourceKind::MeshGeometry);
        reads.push_back(ResourceKind::Color);
        for (const FrameResource& shadow : batchShadowReads(recipe, batch)) reads.push_back(shadow);
        FramePass lights{PassKind::LightBatch,
                         fmt::format("lightBatch {}", batch + 1),
                         anyStrands ? strandReads(recipe, reads) : reads,
                         {ResourceKind::Color},
                         anyStrands || anyMeshes,
                         fmt::format("lights {}-{} of {} (lightsPerPass {}): {} again, colour added, alpha counted "
                                     "once",
                                     recipe.lighting.batches[batch].first + 1, recipe.lighting.batches[batch].second,
                                     lightCount, recipe.lighting.lightsPerPass, drawnAgain)};
        lights.subject = batch;
        graph.add(lights);
    }
}

// The frame's passes, from the recipe (the pass list in RenderPlan.h).
FrameGraph buildFrameGraph(const FrameRecipe& recipe, const Scene& scene, const StrandSummary& strands,
                           const MeshSummary& meshes, bool idsRequested, bool displayOnGpu) {
    FrameGraph graph;
    const bool anyStrands = strands.segments > 0, anyMeshes = meshes.meshes > 0;
    // Why the mesh passes are off, when they are.
    const std::string noMeshes = scene.meshes().empty() ? "no meshes" : "no visible meshes";
    std::vector<std::string> lights;
    for (const PlannedShadow& shadow : recipe.shadows.lights) lights.push_back(shadow.key);
    graph.nameLights(std::move(lights));
    addUploadPasses(graph, recipe, strands, meshes, noMeshes);
    addShadowMapPasses(graph, recipe, anyStrands);

    std::vector<FrameResource> frameImages{ResourceKind::Color, ResourceKind::Depth};
    if (idsRequested) frameImages.push_back(ResourceKind::Ids);
    graph.add(FramePass{PassKind::Clear, "clear", {}, frameImages, true,
                        "the frame's images, empty (transparent black, depth 1, ids -1)"});
    graph.add(meshesPass(frameImages, recipe, meshes, idsRequested, noMeshes));
    graph.add(strandsPass(recipe, strands, idsRequested));
    graph.add(idsPass(recipe, idsRequested, anyStrands, anyMeshes));
    // Light batches add onto the frame's resolved colour, and readback reads
    // it: a multisampled frame is resolved once, here.
    graph.add(FramePass{
        PassKind::Resolve, "resolve", frameImages, frameImages, recipe.transparency.msaaSamples > 0,
        recipe.transparency.msaaSamples > 0
            ? fmt::format("{} samples a pixel averaged (depth and ids: one sample)", recipe.transparency.msaaSamples)
            : "no multisampling"});
    addLightBatchPasses(graph, recipe, anyStrands, anyMeshes);

    graph.add(FramePass{PassKind::Readback, "readback", frameImages, {ResourceKind::Aovs}, true, "the frame's images to the CPU"});
    graph.output(ResourceKind::Aovs);
    graph.add(FramePass{PassKind::DisplayTransform, "displayTransform", {ResourceKind::Color}, {ResourceKind::DisplayImage}, displayOnGpu,
                        displayOnGpu ? "the display image through the display transform's GLSL, on the GPU"
                                     : "no display image asked of the GPU (display transforms run on the CPU)"});
    if (displayOnGpu) graph.output(ResourceKind::DisplayImage);
    graph.compile();
    return graph;
}

}  // namespace

nlohmann::json RenderPlan::toJson(const std::vector<double>& passMilliseconds) const {
    return graph_.toJson(passMilliseconds);
}

bool RenderPlan::shadowUsed(size_t shadow) const {
    const FrameResource hair = recipe_.shadows.resourceOf(shadow), meshes = recipe_.shadows.meshResourceOf(shadow);
    for (const FramePass& pass : graph_.passes())
        if (pass.enabled && (std::find(pass.reads.begin(), pass.reads.end(), hair) != pass.reads.end() ||
                             std::find(pass.reads.begin(), pass.reads.end(), meshes) != pass.reads.end()))
            return true;
    return false;
}

RenderPlan makeRenderPlan(const Scene& scene, const RenderSettings& settings, const CameraView& camera,
                          const StrandSummary& strands, const MeshSummary& meshes,
                          const std::vector<DomeEnvironment>& domes, const PlanRequest& request) {
    FrameRecipe recipe =
        makeFrameRecipe(scene, settings, camera, strands, meshes, domes, request.fallbacks, request.shadowMaps);
    FrameGraph graph = buildFrameGraph(recipe, scene, strands, meshes, request.idsRequested, request.displayOnGpu);
    return RenderPlan(std::move(recipe), std::move(graph));
}

RenderPlan makeRenderPlan(const Scene& scene, const RenderSettings& settings, const CameraView& camera,
                          const StrandSummary& strands, bool idsRequested, const MeshSummary& meshes,
                          bool displayOnGpu, const std::vector<DomeEnvironment>& domes) {
    PlanRequest request;
    request.idsRequested = idsRequested;
    request.displayOnGpu = displayOnGpu;
    return makeRenderPlan(scene, settings, camera, strands, meshes, domes, request);
}

}  // namespace hdhair
