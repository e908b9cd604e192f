#include "hdHair/render/RenderPlan.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "hdHair/render/CameraView.h"
#include "hdHair/render/DeepOpacityLayers.h"
#include "hdHair/render/NearestStrandRule.h"
#include "hdHair/render/RenderSettings.h"
#include "hdHair/scene/Scene.h"

namespace hdhair {

double StrandSummary::meanSegmentsOfAtMost(double length) const {
    double cut = 0.0;
    uint64_t spans = 0;
    for (const std::vector<float>* lengths : spanLengths) {
        for (float span : *lengths) cut += std::isfinite(span) ? std::max(1.0, std::ceil(span / length)) : 1.0;
        spans += lengths->size();
    }
    return spans > 0 ? cut / double(spans) : 0.0;
}

const char* toString(TransparencyPath path) {
    switch (path) {
    case TransparencyPath::Opaque: return "opaque";
    case TransparencyPath::BinSorted: return "binSorted";
    case TransparencyPath::Exact: return "exact";
    case TransparencyPath::Unsorted: return "unsorted";
    }
    return "opaque";
}

const char* toString(ShadowMode mode) {
    switch (mode) {
    case ShadowMode::DeepOpacity: return "deepOpacity";
    case ShadowMode::Reference: return "reference";
    case ShadowMode::Off: return "off";
    }
    return "off";
}

std::string ShadowPlan::resourceOf(const PlannedShadow& shadow) const {
    return (mode == ShadowMode::Reference ? "shadowFragments " : "deepOpacity ") + shadow.key;
}

int ShadowPlan::shadowOf(size_t light) const {
    if (auto shared = sharedMaps.find(light); shared != sharedMaps.end()) light = shared->second;
    for (size_t i = 0; i < lights.size(); ++i)
        if (lights[i].light == light) return int(i);
    return -1;
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

// Where the deep opacity maps are looked up (shadowSampling). Vertex shadows
// interpolate each light's transmittance along a segment, and a map
// resolves it to a texel: what matters is how far apart the points are in
// the finest map's texels (a texel at the casters' nearest depth for a
// perspective light), so spans longer than kVertexShadowTexels of it are cut
// to that length (FrameUniforms::shadowSegmentLength), beyond the error
// rule's cut. vertex always does this, which on stages of long spans costs
// many segments; auto only when that cut alone would average at most
// kVertexShadowSegmentsPerSpan segments a span (real grooms: the TressFX
// bear's and Ratboy's spans, which the error rule cuts about as finely
// anyway), else looks up per fragment; fragment, and reference shadows,
// always per fragment.
void planShadowSampling(ShadowPlan& shadows, const std::string& sampling, const StrandSummary& strands) {
    double finestTexel = 0.0;
    for (const PlannedShadow& shadow : shadows.lights) {
        if (!shadow.view.valid) continue;
        const double texel =
            shadow.view.texelSize * (shadow.view.orthographic ? 1.0 : std::max(shadow.view.nearDepth, 1e-6));
        if (texel > 0.0 && (finestTexel == 0.0 || texel < finestTexel)) finestTexel = texel;
    }
    const double longest = kVertexShadowTexels * finestTexel;
    shadows.perVertex = false;
    shadows.vertexSegmentLength = 0.0;
    shadows.sampling.clear();
    if (shadows.mode != ShadowMode::DeepOpacity || longest <= 0.0) return;
    const double segments = strands.meanSegmentsOfAtMost(longest);
    const std::string counted = fmt::format("spans cut to {} texels of the finest map ({:.3g}) would average {:.2f} "
                                            "segments",
                                            kVertexShadowTexels, longest, segments);
    if (sampling == "fragment") {
        shadows.sampling = "shadows looked up per fragment (shadowSampling=fragment)";
    } else if (sampling == "vertex" || segments <= kVertexShadowSegmentsPerSpan) {
        shadows.perVertex = true;
        shadows.vertexSegmentLength = longest;
        shadows.sampling = fmt::format("shadows looked up per tessellated point: {} (shadowSampling={})", counted,
                                       sampling);
    } else {
        shadows.sampling = fmt::format("shadows looked up per fragment: {}, over {} (shadowSampling=auto)", counted,
                                       kVertexShadowSegmentsPerSpan);
    }
}

// The widest strand, in texels, a light view draws as a line (below).
constexpr double kMaxStrandLineTexels = 1.5;

// Whether a deep opacity map draws the strands as one-texel lines: when none
// is much wider than a texel (the widest authored width, at the casters'
// nearest depth for a perspective view). A ribbon under a texel wide is
// drawn a texel wide with its alpha scaled down (minPixelWidth, at most 1
// for lines to stand in for it); a line carries the same coverage, as alpha
// width / m (strandLinePoint.glsl), without the geometry shader that widens
// each segment. Up to kMaxStrandLineTexels (TressFX's roots are about a texel at
// 512) that alpha may pass 1: the texels a line lights sum the ribbon's
// opacity, in one texel where the ribbon spread it over two, a difference
// within the texel the bilinear lookup blurs over anyway. With `auto` the
// spans the view leaves one segment skip the tessellator too; `tessellated`
// keeps every span on it, the path that check compares against.
void planStrandLines(PlannedShadow& shadow, const ShadowPlan& shadows, const std::string& setting, double maxWidth) {
    const ShadowLightView& view = shadow.view;
    if (!view.valid || shadows.mode != ShadowMode::DeepOpacity) return;
    const double texel = view.orthographic ? view.texelSize : view.texelSize * view.nearDepth;
    shadow.widestTexels = texel > 0.0 ? maxWidth / texel : std::numeric_limits<double>::infinity();
    shadow.strandLines = setting != "off" && shadows.minPixelWidth <= 1.0 && shadow.widestTexels <= kMaxStrandLineTexels;
    shadow.straightSpans = shadow.strandLines && setting == "auto";
}

// The shadow settings, and a planned shadow for every light that casts one
// (its view fitted to the casters, or why it cannot be).
void planShadows(RenderPlan& plan, const RenderSettings& settings, const StrandSummary& strands, bool anyMeshes) {
    ShadowPlan& shadows = plan.shadows;
    const std::string mode = settings.getToken("shadowMode");
    shadows.mode = mode == "reference" ? ShadowMode::Reference : mode == "off" ? ShadowMode::Off
                                                                                 : ShadowMode::DeepOpacity;
    shadows.layers = settings.getInt("shadowLayers");
    shadows.boundaries = deepOpacityLayerBoundaries(
        shadows.layers,
        settings.getToken("shadowLayerSpacing") == "uniform" ? ShadowLayerSpacing::Uniform : ShadowLayerSpacing::Linear);
    shadows.layerDepth = settings.getFloat("shadowLayerDepth");
    shadows.bilinear = settings.getToken("shadowFilter") == "bilinear";
    shadows.resolution = settings.getInt("shadowMapResolution");
    shadows.minPixelWidth = settings.getFloat("minPixelWidth");
    shadows.tessellationTolerance = settings.getFloat("shadowTessellationTolerance");
    shadows.meshesCast = anyMeshes && shadows.mode != ShadowMode::Off;
    shadows.maxMaps = shadowMapBudget(shadows.resolution, shadows.layers, settings.getInt("shadowMemoryMB"));
    size_t mapped = 0;
    for (size_t i = 0; i < plan.lights.lights.size(); ++i) {
        const ShadingLight& light = plan.lights.lights[i];
        if (!light.castsShadow) continue;
        PlannedShadow shadow;
        shadow.light = i;
        shadow.key = light.path.empty() ? "camera light" : light.path;
        if (shadows.mode != ShadowMode::Off) {
            if (mapped < shadows.maxMaps) {
                shadow.view = fitShadowLightView(light, strands.casters, shadows.resolution);
                mapped += shadow.view.valid ? 1 : 0;
            } else {
                shadow.view.valid = false;
                shadow.overBudget = true;
                shadow.view.fallback = fmt::format("shadowMemoryMB={} holds {} maps of {}x{} texels",
                                                   settings.getInt("shadowMemoryMB"), shadows.maxMaps,
                                                   shadows.resolution, shadows.resolution);
                shadows.overBudget += 1;
            }
        }
        planStrandLines(shadow, shadows, settings.getToken("shadowStrandLines"), strands.casters.maxWidth);
        shadows.lights.push_back(std::move(shadow));
    }
    planShadowSampling(shadows, settings.getToken("shadowSampling"), strands);
    if (shadows.mode == ShadowMode::DeepOpacity && settings.getToken("domeShadowFilter") == "mipmap")
        for (size_t i = 0; i < plan.lights.lights.size() && !shadows.convolvedOpacity; ++i)
            shadows.convolvedOpacity = plan.lights.lights[i].isSrbf() && shadows.shadowOf(i) >= 0;
}

// The passes that build light `shadow`'s map, wanted or not with the reason.
void addShadowPasses(FrameGraph& graph, const RenderPlan& plan, const PlannedShadow& shadow, bool anyStrands) {
    const ShadowPlan& shadows = plan.shadows;
    bool wanted = false;
    std::string why, flat;
    if (shadows.mode == ShadowMode::Off) {
        why = "shadowMode=off";
    } else if (!anyStrands) {
        why = "no visible curves";
    } else if (!shadow.view.valid) {
        why = "no shadows from this light: " + shadow.view.fallback;
    } else {
        wanted = true;
        why = fmt::format("{} light view, {}x{}", shadow.view.orthographic ? "orthographic" : "perspective",
                          shadows.resolution, shadows.resolution);
        if (plan.flatShading) flat = "; every prim is flat-shaded, so no pass reads lights or their shadows";
    }
    const std::string& key = shadow.key;
    if (shadows.mode == ShadowMode::Reference) {
        graph.add(FramePass{"shadowFragments " + key, {"strands"}, {"shadowFragments " + key}, wanted,
                            why + (wanted ? ": every fragment kept per texel, the reference (slow)" : "") + flat});
    } else {
        // How the strands are drawn there, when they are.
        const std::string drawn =
            !wanted ? ""
            : shadow.strandLines
                ? fmt::format("; strands as one-texel lines (the widest is {:.2f} texels){}", shadow.widestTexels,
                              shadow.straightSpans ? ", spans of one segment without the tessellator"
                                                   : ", every span through the tessellator (shadowStrandLines=tessellated)")
                : fmt::format("; strands as ribbons ({})",
                              shadow.widestTexels > kMaxStrandLineTexels
                                  ? fmt::format("the widest is {:.2f} texels", shadow.widestTexels)
                              : shadows.minPixelWidth > 1.0 ? "minPixelWidth above 1"
                                                            : "shadowStrandLines=off");
        graph.add(FramePass{"shadowDepth " + key, {"strands"}, {"hairDepth " + key}, wanted,
                            why + (wanted ? ": the nearest hair per texel" : "") + drawn + flat});
        graph.add(FramePass{"deepOpacity " + key, {"strands", "hairDepth " + key}, {"deepOpacity " + key}, wanted,
                            (wanted ? why + fmt::format(": {} opacity layers behind it, the last {} of the hair's "
                                                        "depth along the light",
                                                        shadows.layers, shadows.layerDepth)
                                    : why) +
                                drawn + flat});
    }
    if (shadows.meshesCast)
        graph.add(FramePass{"meshShadow " + key, {"meshGeometry"}, {shadows.meshResourceOf(shadow)}, wanted,
                            why + (wanted ? ": the nearest mesh per texel, opaque: the hair behind it is unlit" : "") +
                                flat});
}

// The opacity layers of every map averaged into a mip chain ("opacityMipmaps").
const FrameResource kConvolvedOpacity = "convolvedOpacity";

// The shadow maps light batch `batch` reads: those of its lights that have
// one, and the mip chain when its SRBF lights read through it.
std::vector<FrameResource> batchShadowReads(const RenderPlan& plan, size_t batch) {
    std::vector<FrameResource> reads;
    if (plan.shadows.mode == ShadowMode::Off) return reads;
    bool srbfMapRead = false;
    for (size_t light = plan.lightBatches[batch].first; light < plan.lightBatches[batch].second; ++light) {
        int shadow = plan.shadows.shadowOf(light);
        if (shadow < 0 || !plan.shadows.lights[size_t(shadow)].view.valid) continue;
        srbfMapRead = srbfMapRead || plan.lights.lights[light].isSrbf();
        const FrameResource map = plan.shadows.resourceOf(plan.shadows.lights[size_t(shadow)]);
        // SRBF lights share maps (ShadowPlan::sharedMaps): each read once.
        if (std::find(reads.begin(), reads.end(), map) != reads.end()) continue;
        reads.push_back(map);
        if (plan.shadows.meshesCast) reads.push_back(plan.shadows.meshResourceOf(plan.shadows.lights[size_t(shadow)]));
    }
    // Its SRBF lights that read a map read it through the mip chain (which
    // "opacityMipmaps" makes whenever an SRBF light has a map).
    if (plan.shadows.convolvedOpacity && srbfMapRead) reads.push_back(kConvolvedOpacity);
    return reads;
}

}  // namespace

void RenderPlan::setShadowMap(size_t shadow, int slot, bool rebuild, const std::string& reason) {
    PlannedShadow& planned = shadows.lights[shadow];
    planned.slot = slot;
    planned.rebuild = rebuild;
    planned.reason = reason;
    for (const char* kind : {"shadowDepth ", "deepOpacity ", "shadowFragments ", "meshShadow "}) {
        FramePass* pass = graph.find(kind + planned.key);
        if (!pass || !pass->wanted) continue;
        if (rebuild) {
            pass->reason = reason + "; " + pass->reason;
        } else {
            pass->wanted = false;
            pass->reason = reason;
        }
    }
    if (!rebuild) {
        graph.input(shadows.resourceOf(planned));
        if (shadows.meshesCast) graph.input(shadows.meshResourceOf(planned));
    }
    graph.compile();
}

bool RenderPlan::shadowUsed(size_t shadow) const {
    const std::string resource = shadows.resourceOf(shadows.lights[shadow]);
    for (const FramePass& pass : graph.passes())
        if (pass.enabled && std::find(pass.reads.begin(), pass.reads.end(), resource) != pass.reads.end())
            return true;
    return false;
}

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
        } else if (pass.name == "strands" || pass.name.rfind("lightBatch", 0) == 0) {
            // The strands now read the draw order; what else they read stays.
            auto drawsStrands = std::find(pass.reads.begin(), pass.reads.end(), "strands");
            if (drawsStrands == pass.reads.end()) continue;
            std::vector<FrameResource> rest;
            for (const FrameResource& read : pass.reads)
                if (read != "strands" && read != "drawOrder") rest.push_back(read);
            pass.reads = strandReads(transparency, rest);
        }
    }
    graph.compile();
}

size_t shadowMapBudget(int resolution, int layers, int memoryMB) {
    constexpr size_t kGuaranteedArrayLayers = 2048;  // GL 4.5's minimum GL_MAX_ARRAY_TEXTURE_LAYERS
    const size_t targets = size_t((layers + 3) / 4);
    const double bytesPerMap = double(resolution) * double(resolution) * (4.0 + 4.0 + 8.0 * double(targets));
    const double fitting = std::floor(double(memoryMB) * 1024.0 * 1024.0 / bytesPerMap);
    const size_t limit = std::min(kGuaranteedArrayLayers / targets, size_t(std::min(fitting, 1e9)));
    if (limit == 0) return 0;
    size_t maps = 1;
    while (maps * 2 <= limit) maps *= 2;
    return maps;
}

nlohmann::json RenderPlan::toJson() const { return graph.toJson(); }

bool usesCameraLight(const std::string& cameraLightSetting, bool stageHasLight, bool anythingLit) {
    return anythingLit && (cameraLightSetting == "on" || (cameraLightSetting == "auto" && !stageHasLight));
}

RenderPlan makeRenderPlan(const Scene& scene, const RenderSettings& settings, const CameraView& camera,
                          const StrandSummary& strands, bool idsRequested, const MeshSummary& meshes,
                          bool displayOnGpu, const std::vector<DomeEnvironment>& domes) {
    RenderPlan plan;
    // domeLighting=srbf or sampled: domes are SRBF lights and a uniform term,
    // or sampled distant lights (DomeLighting.h), not toShadingLights' flat
    // ambient.
    const bool domesAsLights = domeLightingMode(settings) != DomeLightingMode::Ambient;
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
            plan.lightsOverCap += 1;
        }
    }
    plan.lights = toShadingLights(stageLights);
    if (domesAsLights)
        plan.domes = addDomeLights(scene, domes, settings.getInt("domeShadowLights"), plan.lights,
                                   plan.shadows.sharedMaps);
    const bool anyMeshes = meshes.meshes > 0;
    // Meshes are lit unless the shadingModel setting asks for flat
    // displayColor (hair prims may still choose their own model).
    plan.meshesLit = anyMeshes && settings.getToken("shadingModel") != "flat";
    plan.flatShading = !strands.anyLit && !plan.meshesLit;

    std::string cameraLight = settings.getToken("cameraLight");
    bool stageHasLight = !plan.lights.lights.empty() || glm::length(plan.lights.ambient) > 0.0f ||
                         glm::length(plan.lights.uniformDome) > 0.0f;
    plan.cameraLight = usesCameraLight(cameraLight, stageHasLight, !plan.flatShading);
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
    // Light colours (and colour temperatures) are linear Rec.709, as every
    // authored colour: shading happens in the rendering space.
    const glm::mat3 toRenderingSpace = rec709To(settings.renderingSpace());
    for (ShadingLight& light : plan.lights.lights) light.scale = toRenderingSpace * light.scale;
    plan.lights.ambient = toRenderingSpace * plan.lights.ambient;
    plan.lights.uniformDome = toRenderingSpace * plan.lights.uniformDome;

    planShadows(plan, settings, strands, anyMeshes);

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
    const size_t perPass = size_t(settings.getInt("lightsPerPass"));
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

    size_t lightCount = plan.flatShading ? 0 : plan.lights.lights.size();
    for (size_t begin = 0; begin < lightCount; begin += perPass)
        plan.lightBatches.emplace_back(begin, std::min(begin + perPass, lightCount));
    if (plan.lightBatches.empty()) plan.lightBatches.emplace_back(0, 0);

    for (const PlannedShadow& shadow : plan.shadows.lights) addShadowPasses(graph, plan, shadow, anyStrands);
    if (plan.shadows.convolvedOpacity) {
        // After every map it averages: the chain covers the whole array.
        // Wanted exactly when a batch reads the chain: an SRBF light has a
        // map (batchShadowReads); no strands, no valid light views.
        FramePass mipmaps{"opacityMipmaps", {}, {kConvolvedOpacity}, true, ""};
        size_t lobes = 0;
        for (const PlannedShadow& shadow : plan.shadows.lights)
            if (shadow.view.valid) {
                mipmaps.reads.push_back(plan.shadows.resourceOf(shadow));
                lobes += plan.lights.lights[shadow.light].isSrbf() ? 1 : 0;
            }
        mipmaps.wanted = lobes > 0;
        mipmaps.reason = mipmaps.wanted ? fmt::format("the opacity layers of {} SRBF light map(s) averaged into a mip "
                                                      "chain: the convolution optical depth map their lookups widen "
                                                      "over with depth (domeShadowFilter=mipmap; Ren et al. 2010 §5)",
                                                      lobes)
                                        : "no SRBF light has a map";
        graph.add(mipmaps);
    }

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
    if (!plan.flatShading)
        for (const PlannedDome& dome : plan.domes) shading += "; " + dome.describe(perPass);
    if (!plan.flatShading && !plan.shadows.sampling.empty()) shading += "; " + plan.shadows.sampling;
    std::string multisampling =
        plan.msaaSamples > 0 ? fmt::format(", {}x MSAA", plan.msaaSamples) : std::string();
    // The strand pass writes ids itself where it can keep the nearest
    // fragment's (opaque, and exact's resolve).
    std::vector<FrameResource> strandWrites{"color", "depth"};
    if (idsRequested && (plan.transparency == TransparencyPath::Opaque || plan.transparency == TransparencyPath::Exact))
        strandWrites.push_back("ids");
    std::vector<FrameResource> inPlace = strandWrites;
    for (const FrameResource& shadow : batchShadowReads(plan, 0)) inPlace.push_back(shadow);
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

    const std::string drawnAgain = anyStrands && anyMeshes ? "the meshes and the strands"
                                   : anyMeshes                ? "the meshes"
                                                              : "the strands";
    for (size_t batch = 1; batch < plan.lightBatches.size(); ++batch) {
        // A later batch draws what the first drew, with its own lights and their shadows.
        std::vector<FrameResource> batchReads;
        if (anyMeshes) batchReads.push_back("meshGeometry");
        batchReads.push_back("color");
        for (const FrameResource& shadow : batchShadowReads(plan, batch)) batchReads.push_back(shadow);
        FramePass lights{fmt::format("lightBatch {}", batch + 1),
                         anyStrands ? strandReads(plan.transparency, batchReads) : batchReads, {"color"},
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
