#include "hdHair/render/Renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <tuple>
#include <vector>

#include <fmt/format.h>
#include <glad/gl.h>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <tbb/parallel_for.h>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/curves/CatmullRomEvaluation.h"
#include "hdHair/gl/GlRenderThread.h"
#include "hdHair/gl/GpuMemory.h"
#include "hdHair/render/BinSort.h"
#include "hdHair/render/FrameMemory.h"
#include "hdHair/render/FrameResources.h"
#include "hdHair/render/FrameScheduler.h"
#include "hdHair/render/InteractivePreview.h"
#include "hdHair/plan/NearestStrandRule.h"
#include "hdHair/plan/SettingOrigins.h"
#include "hdHair/render/StrandShadingFeatures.h"
#include "hdHair/render/SupersampleResolve.h"
#include "hdHair/scene/Scene.h"
#include "hdHair/scene/MeshPrim.h"
#include "hdHair/scene/SceneValidation.h"
#include "hdHair/shading/MarschnerTables.h"

namespace hdhair {
namespace {

using Clock = std::chrono::steady_clock;

// --stats' shadowMaps: each planned shadow's map, rebuilt, kept or none, and why.
void reportShadowMaps(const ShadowPlan& shadows, const ShadowMapAssignment& assignment, RenderStats& stats) {
    stats.shadowMapsRebuilt = stats.shadowMapsKept = 0;
    stats.shadowMaps = nlohmann::json::array();
    for (size_t i = 0; i < shadows.lights.size(); ++i) {
        const PlannedShadow& shadow = shadows.lights[i];
        const std::optional<ShadowMapAssignment::Map>& map = assignment.maps[i];
        const bool mapped = map && map->slot >= 0;
        if (mapped) (map->rebuild ? stats.shadowMapsRebuilt : stats.shadowMapsKept) += 1;
        stats.shadowMaps.push_back({{"light", shadow.key},
                                    {"map", mapped ? (map->rebuild ? "rebuilt" : "kept") : "none"},
                                    {"reason", map ? map->reason
                                               : shadows.mode == ShadowMode::Off ? std::string("shadowMode=off")
                                               : !shadow.view.valid              ? shadow.view.fallback
                                                                                 : std::string("nothing reads it")}});
    }
}

double millisecondsSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

gl::FrameUniforms frameUniforms(const CameraView& camera, const FrameRecipe& recipe) {
    gl::FrameUniforms frame;
    frame.viewProjection = glm::mat4(camera.projection * camera.view);
    frame.cameraPosition = glm::vec4(glm::vec3(camera.position()), camera.orthographic ? 0.0f : 1.0f);
    frame.cameraForward = glm::vec4(glm::vec3(camera.forward()), 0.0f);
    frame.viewportSize = glm::vec2(float(camera.imageWidth), float(camera.imageHeight));
    frame.pixelsPerSegment = float(recipe.tessellation.pixelsPerSegment);
    frame.tessellationTolerance = float(recipe.tessellation.tolerance);
    frame.maxSegmentsPerSpan = float(recipe.tessellation.maxSegmentsPerSpan);
    frame.pixelsPerUnit = float(camera.pixelsPerUnit());
    frame.minPixelWidth = float(recipe.tessellation.minPixelWidth);
    frame.drawMode = recipe.transparency.path == TransparencyPath::Opaque ? 0 : 1;
    frame.orderedDraw = recipe.drawsSorted() ? 1 : 0;
    frame.nearestStrandMinAlpha = kNearestStrandMinAlpha;
    const glm::mat3 toRec709 = glm::inverse(rec709To(recipe.lighting.renderingSpace));
    for (int column = 0; column < 3; ++column) frame.colorToRec709[column] = glm::vec4(toRec709[column], 0.0f);
    frame.shadowSegmentLength = float(recipe.shadows.vertexSegmentLength);
    return frame;
}

// The clip w of the curves' bounds at their nearest (`nearest`) or farthest
// corner: w is linear, so its extremes over the box are at corners. 1 for
// orthographic cameras, where widths do not shrink with depth.
double boundsClipW(const CameraView& camera, const PreparedCurves& curves, bool nearest) {
    if (camera.orthographic) return 1.0;
    double extreme = nearest ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity();
    for (int corner = 0; corner < 8; ++corner) {
        glm::dvec3 p((corner & 1) ? curves.boundsMax.x : curves.boundsMin.x,
                     (corner & 2) ? curves.boundsMax.y : curves.boundsMin.y,
                     (corner & 4) ? curves.boundsMax.z : curves.boundsMin.z);
        const double w = (camera.projection * camera.view * glm::dvec4(p, 1.0)).w;
        extreme = nearest ? std::min(extreme, w) : std::max(extreme, w);
    }
    return extreme;
}

// The thinnest projected width of any strand: its thinnest span end at the
// farthest depth of its bounds (a lower bound for perspective cameras).
double minProjectedWidthPixels(const CameraView& camera, const PreparedCurves& curves, float minSpanWidth) {
    const double farthest = boundsClipW(camera, curves, false);
    if (farthest <= 0.0) return std::numeric_limits<double>::infinity();  // behind the camera
    return double(minSpanWidth) * camera.pixelsPerUnit() / farthest;
}

// The widest projected width of any strand: its widest control point at the
// nearest depth of its bounds (an upper bound); infinity when the bounds
// reach the camera's plane.
double maxProjectedWidthPixels(const CameraView& camera, const PreparedCurves& curves, float maxWidth) {
    const double nearest = boundsClipW(camera, curves, true);
    if (nearest <= 0.0) return std::numeric_limits<double>::infinity();
    return double(maxWidth) * camera.pixelsPerUnit() / nearest;
}

// About how many fragments a span of the prim covers: a ribbon of the
// spans' mean length and mean drawn width (at least a pixel, the coverage
// rule), projected at the middle depth of the prim's bounds, covers about
// (length + width) x width pixels. Infinity when the bounds reach the
// camera's plane.
double fragmentsPerSpanEstimate(const CameraView& camera, const PreparedCurves& curves, float meanSpanLength,
                                float meanSpanWidth) {
    const double nearest = boundsClipW(camera, curves, true);
    if (nearest <= 0.0) return std::numeric_limits<double>::infinity();
    const double pixelsPerUnit = camera.pixelsPerUnit() / (0.5 * (nearest + boundsClipW(camera, curves, false)));
    const double length = double(meanSpanLength) * pixelsPerUnit;
    const double width = std::max(1.0, double(meanSpanWidth) * pixelsPerUnit);
    return (length + width) * width;
}

// An abandoned attempt ran its upload passes (runsWhenStopped): the strands,
// materials and meshes it sent are on the GPU, and the next attempt sends
// nothing again.
void keepUploadsOfAbandonedAttempt(FrameInputs& inputs) {
    inputs.uploads.writes.clear();
    inputs.materials.reset();
    inputs.meshes.changed = false;
}

// The instances of an instanced prim are copies of its first instance but for
// the transform (HdHairRenderParam::SetCurves, SetMesh), so whatever their
// data needs repaired is the first instance's again: only the first reports
// it, and a PointInstancer of 10,000 strands warns once, not 10,000 times.
template <typename Prim>
Diagnostics& reportingFor(const Prim& prim, Diagnostics& diagnostics, Diagnostics& repeated) {
    return prim.instanceId == 0 ? diagnostics : repeated;
}

// The last guard of "no NaN or Inf in any AOV": what the checks of the
// inputs (SceneValidation.h, curve and material repairs) did not catch, say a
// finite light so strong that shading overflows float, is replaced here and
// counted in a warning, so an output never carries a value a compositor
// cannot use. NaN becomes 0, infinities the largest float of their sign.
void replaceNonFinitePixels(RenderResult& result, Diagnostics& diagnostics) {
    auto replace = [](Image& image) {
        size_t replaced = 0;
        const size_t channels = size_t(std::max(image.channels, 1));
        for (size_t i = 0; i < image.pixels.size(); i += channels) {
            bool bad = false;
            for (size_t c = i; c < i + channels && c < image.pixels.size(); ++c) {
                float& value = image.pixels[c];
                if (std::isfinite(value)) continue;
                bad = true;
                value = std::isnan(value) ? 0.0f : std::copysign(std::numeric_limits<float>::max(), value);
            }
            replaced += bad ? 1 : 0;
        }
        return replaced;
    };
    const size_t color = replace(result.color), depth = replace(result.depth), display = replace(result.display);
    if (color + depth + display > 0)
        diagnostics.warn("render", fmt::format("{} colour, {} depth and {} display pixels were not finite (NaN or "
                                               "beyond float range); NaN written as 0, infinities as the largest "
                                               "float",
                                               color, depth, display));
}

}  // namespace

Renderer::Renderer(gl::GlBackend backend) : glThread_(std::make_unique<gl::GlRenderThread>(backend)) {
    glThread_->run([this] { resources_ = std::make_unique<FrameResources>(); });
    passTiming_ = gl::passTimingFor(glThread_->contextDescription());
}

Renderer::~Renderer() {
    // GL objects die on the thread that owns the context.
    glThread_->run([this] { resources_.reset(); });
}

const std::string& Renderer::glDescription() const { return glThread_->contextDescription(); }

const std::string& Renderer::glDevice() const { return glThread_->contextOrigin(); }

void Renderer::prepareChangedCurves(const Scene& scene, const RenderSettings& settings, Diagnostics& diagnostics) {
    Clock::time_point start = Clock::now();
    const RenderingSpace space = settings.renderingSpace();
    for (auto it = curves_.begin(); it != curves_.end();)
        it = scene.curves().count(it->first) ? std::next(it) : curves_.erase(it);
    // Prepare changed prims in parallel: curve preparation is CPU work
    // without GL, thread-safe across prims.
    struct Change {
        const CurvesPrim* prim;
        const MaterialPrim* material;
        CachedCurves* cached;
    };
    std::vector<Change> changed;
    for (const auto& [path, entry] : scene.curves()) {
        CachedCurves& cached = curves_[path];
        const SceneEntry<MaterialPrim>* material = scene.findMaterial(entry.prim->materialBinding);
        const uint64_t materialVersion = material ? material->version : 0;
        if (cached.prepared && cached.version == entry.version && cached.colorMaterialVersion == materialVersion &&
            cached.space == space)
            continue;
        cached.version = entry.version;
        cached.colorMaterialVersion = materialVersion;
        cached.space = space;
        changed.push_back({entry.prim.get(), material ? material->prim.get() : nullptr, &cached});
    }
    Diagnostics repeated;  // later instances' repairs (reportingFor)
    tbb::parallel_for(size_t(0), changed.size(), [&](size_t i) {
        Diagnostics& report = reportingFor(*changed[i].prim, diagnostics, repeated);
        const StrandColorSource colors = strandColorSource(*changed[i].prim, changed[i].material, report);
        auto prepared = std::make_shared<PreparedCurves>(
            prepareCurves(*changed[i].prim, report, hairParameterPrimvars(), &colors));
        // Authored colours are linear Rec.709; shading happens in the
        // rendering space (Marschner's absorption from colour included).
        if (space != RenderingSpace::LinearRec709)
            for (StrandControlPoint& point : prepared->controlPoints) point.color = toRenderingSpace(space, point.color);
        CachedCurves& cached = *changed[i].cached;
        cached.minSpanWidth = std::numeric_limits<float>::max();
        cached.maxWidth = 0.0f;
        cached.fullyOpaque = true;
        for (const StrandControlPoint& point : prepared->controlPoints) {
            cached.fullyOpaque = cached.fullyOpaque && point.opacity == 1.0f;
            if (std::isfinite(point.width)) cached.maxWidth = std::max(cached.maxWidth, point.width);
        }
        cached.spanLengths.clear();
        cached.spanLengths.reserve(prepared->segmentCount());
        double lengthSum = 0.0, widthSum = 0.0;
        for (size_t s = 0; s < prepared->segmentCount(); ++s) {
            const StrandControlPoint* controls = prepared->spanControls(s);
            cached.minSpanWidth = std::min({cached.minSpanWidth, controls[1].width, controls[2].width});
            cached.spanLengths.push_back(bezierPolygonLength(controls));
            if (std::isfinite(cached.spanLengths.back())) lengthSum += cached.spanLengths.back();
            const double width = 0.5 * (double(controls[1].width) + double(controls[2].width));
            if (std::isfinite(width)) widthSum += width;
        }
        const double spans = double(std::max<size_t>(prepared->segmentCount(), 1));
        cached.meanSpanLength = float(lengthSum / spans);
        cached.meanSpanWidth = float(widthSum / spans);
        cached.sortHashes = segmentSortHashes(*prepared);
        cached.prepared = std::move(prepared);
        cached.material.reset();
        cached.parameterPoints.clear();
    });
    pendingPrepareMilliseconds_ += millisecondsSince(start);
    pendingPreparedPrims_ += changed.size();
}

SceneBounds Renderer::prepare(const Scene& scene, const RenderSettings& settings, Diagnostics& diagnostics) {
    prepareChangedCurves(scene, settings, diagnostics);
    std::vector<FramingPoints> prims;
    for (const auto& [path, entry] : scene.curves()) {
        const CachedCurves& cached = curves_.at(path);
        if (!entry.prim->visible || cached.prepared->empty()) continue;
        prims.push_back(spanFramingPoints(*cached.prepared));
    }
    for (const auto& [path, entry] : scene.meshes()) {
        if (!entry.prim->visible || !isFiniteTransform(entry.prim->worldTransform)) continue;
        prims.push_back(meshFramingPoints(*entry.prim));
    }
    return framingBounds(prims, diagnostics);
}

void Renderer::prepareMeshes(const Scene& scene, const RenderSettings& settings, Diagnostics& diagnostics) {
    for (auto it = meshes_.begin(); it != meshes_.end();)
        it = scene.meshes().count(it->first) ? std::next(it) : meshes_.erase(it);
    struct Change {
        const MeshPrim* prim;
        CachedMesh* cached;
    };
    std::vector<Change> changed;
    const int settingLevel = settings.values().meshRefineLevel;
    for (const auto& [path, entry] : scene.meshes()) {
        CachedMesh& cached = meshes_[path];
        const int level = entry.prim->refineLevel >= 0 ? entry.prim->refineLevel : settingLevel;
        if (cached.prepared && cached.version == entry.version && cached.refineLevel == level &&
            cached.space == settings.renderingSpace())
            continue;
        cached.version = entry.version;
        cached.refineLevel = level;
        cached.space = settings.renderingSpace();
        changed.push_back({entry.prim.get(), &cached});
    }
    Diagnostics repeated;  // later instances' repairs (reportingFor)
    tbb::parallel_for(size_t(0), changed.size(), [&](size_t i) {
        Diagnostics& report = reportingFor(*changed[i].prim, diagnostics, repeated);
        auto prepared =
            std::make_shared<PreparedMesh>(prepareMesh(*changed[i].prim, changed[i].cached->refineLevel, report));
        // Mesh colours, like the hair's, are linear Rec.709 taken into the rendering space.
        for (MeshVertex& vertex : prepared->vertices)
            vertex.color = toRenderingSpace(changed[i].cached->space, vertex.color);
        changed[i].cached->prepared = std::move(prepared);
    });
    pendingPreparedMeshes_ += changed.size();
}

MeshUpload Renderer::meshUpload(const Scene& scene, MeshSummary& summary) {
    MeshUpload upload;
    std::vector<std::pair<std::shared_ptr<const PreparedMesh>, glm::ivec2>> drawn;
    for (const auto& [path, entry] : scene.meshes()) {
        const std::shared_ptr<const PreparedMesh>& prepared = meshes_.at(path).prepared;
        if (!entry.prim->visible || prepared->empty()) continue;
        const glm::ivec2 ids(entry.prim->primId, entry.prim->instanceId);
        upload.draws.push_back(gl::MeshDraw{upload.vertices, prepared->vertices.size(), ids});
        upload.vertices += prepared->vertices.size();
        upload.meshes.push_back(prepared);
        drawn.emplace_back(prepared, ids);
        summary.minRefineLevel = summary.meshes == 0 ? prepared->refineLevel
                                                     : std::min(summary.minRefineLevel, prepared->refineLevel);
        summary.maxRefineLevel = std::max(summary.maxRefineLevel, prepared->refineLevel);
        summary.meshes += 1;
        summary.triangles += prepared->triangleCount();
        summary.bounds = unite(summary.bounds, CasterBounds{prepared->boundsMin, prepared->boundsMax, 0.0});
    }
    upload.changed = drawn != uploadedMeshes_;
    summary.changed = upload.changed;
    uploadedMeshes_ = std::move(drawn);
    return upload;
}

ShadowMapAssignment Renderer::decideShadowMaps(const RenderPlan& plan, const StrandSummary& summary,
                                               const FrameFallbacks& fallbacks, Diagnostics& diagnostics,
                                               RenderStats& stats) {
    const FrameRecipe& recipe = plan.recipe();
    const ShadowPlan& shadows = recipe.shadows;
    ShadowMapAssignment assignment;
    assignment.maps.resize(shadows.lights.size());
    std::vector<ShadowMapRequest> requests;
    std::vector<size_t> requested;  // index into shadows.lights
    for (size_t i = 0; i < shadows.lights.size(); ++i) {
        const PlannedShadow& shadow = shadows.lights[i];
        // The camera light, when used, is the last light.
        const bool followsCamera =
            recipe.lighting.cameraLight && shadow.light + 1 == recipe.lighting.lights.lights.size();
        if (shadows.mode != ShadowMode::Off && !recipe.lighting.flatShading && summary.segments > 0 &&
            !shadow.view.valid && !shadow.overBudget && !shadow.byVolume)
            diagnostics.warn(shadow.key, "no shadows from this light: " + shadow.view.fallback);
        if (!shadow.meshFallback.empty() && !recipe.lighting.flatShading) diagnostics.warn(shadow.key, shadow.meshFallback);
        if (!plan.shadowUsed(i)) continue;
        if (auto unbuildable = fallbacks.unbuildableShadows.find(shadow.key);
            unbuildable != fallbacks.unbuildableShadows.end()) {
            assignment.maps[i] = ShadowMapAssignment::Map{-1, false, "no map: " + unbuildable->second};
            continue;
        }
        requests.push_back({shadow.key, shadow.view, followsCamera, shadow.meshView});
        requested.push_back(i);
    }
    if (shadows.volumeCoarsened && !recipe.lighting.flatShading && plan.isEnabled(PassKind::DensityVolume))
        diagnostics.warn("render", "the hair density volume: " + shadows.volumeNote +
                                       "; its shadows are blurred over the larger voxels (raise "
                                       "densityVolumeMemoryMB for the finer grid)");
    // domeLighting=sampled throws over budget when it is planned (planShadows).
    const bool shadowsDrawn = shadows.overBudget > 0 && !recipe.lighting.flatShading && summary.segments > 0;
    if (shadowsDrawn)
        diagnostics.warn("render", fmt::format("{} lights cast shadows, more than the {} maps shadowMemoryMB={} holds "
                                               "at shadowMapResolution={}; the last {} in path order shade "
                                               "unshadowed",
                                               shadows.lights.size(), shadows.maxMaps,
                                               shadows.memoryMB, shadows.resolution,
                                               shadows.overBudget));
    const ShadowFrame frame = shadowMaps_.update(requests, shadows, castersVersion_, shadows.mode == ShadowMode::Reference);
    assignment.capacity = frame.capacity;
    for (size_t r = 0; r < requests.size(); ++r) {
        const ShadowMapDecision& decision = frame.maps[r];
        assignment.maps[requested[r]] = ShadowMapAssignment::Map{decision.slot, decision.rebuild, decision.reason};
    }
    reportShadowMaps(shadows, assignment, stats);
    return assignment;
}

namespace {

// The first layer of `texels` (`layers` layers of width × height) in the
// upload's stack, added at its end unless already there. Every table has
// the Marschner tables' layer size.
int tableLayer(MaterialUpload& upload, const std::vector<uint16_t>& texels, int width, int height, int layers) {
    int first = 0;
    for (const gl::MaterialTableLayers& table : upload.tables) {
        if (table.halfTexels == &texels) return first;
        first += table.layers;
    }
    upload.tables.push_back({&texels, layers});
    upload.tableWidth = width;
    upload.tableHeight = height;
    return first;
}

}  // namespace

std::optional<MaterialUpload> Renderer::materialUpload(const std::vector<HairMaterial>& materials,
                                                      const std::vector<CachedCurves*>& drawnCurves,
                                                      const std::vector<DrawnPrim>& drawn,
                                                      const StrandUploadPlan& uploads, bool srbfTables,
                                                      Diagnostics& diagnostics) {
    if (materials == uploadedMaterials_ && uploads.ranges == materialRanges_ &&
        uploads.firstControls == materialFirstControls_ && srbfTables == materialSrbfTables_)
        return std::nullopt;
    MaterialUpload upload;
    if (srbfTables) upload.srbfTables = srbfTables_.tablesFor(materials, diagnostics);
    for (const HairMaterial& material : materials) {
        gl::GpuHairMaterial entry;
        entry.modelAndLayer = glm::ivec4(int(material.model), 0, 0, 0);
        entry.kajiyaKay = glm::vec4(material.kajiyaKay.diffuse, material.kajiyaKay.specular,
                                    material.kajiyaKay.shininess, 0.0f);
        const MarschnerParameters& marschner = material.marschner;
        entry.alphaEta = glm::vec4(marschner.alpha, marschner.eta);
        entry.betaGlint = glm::vec4(marschner.beta, marschner.glintScale);
        entry.sigmaA = glm::vec4(marschner.sigmaA, marschner.causticWidth);
        entry.caustic = glm::vec4(marschner.causticFade, marschner.causticLimit, 0.0f, 0.0f);
        if (material.analyticAzimuthal) entry.modelAndLayer.z |= gl::kHairMaterialAnalytic;
        if (srbfTables) {
            const glm::ivec2 tables = upload.srbfTables.materialTables[upload.materials.size()];
            entry.segments.y = tables.x;  // srbfLighting.glsl: the table, and its uniform-dome row
            entry.segments.z = tables.y;
            if (srbfAbsorbsPerFragment(material)) entry.modelAndLayer.z |= gl::kHairMaterialSrbfLobes;
        }
        if (material.usesTables()) {
            // Tables depend on eta, absorption and glints only: built once per
            // distinct set and kept for later frames.
            auto cached = std::find_if(marschnerTables_.begin(), marschnerTables_.end(),
                                       [&](const CachedTables& c) { return c.material.sharesTablesWith(material); });
            if (cached == marschnerTables_.end()) {
                MarschnerTables built = buildMarschnerTables(material.marschner);
                marschnerTables_.push_back({material, built.halfTexels(), built.width, built.height});
                cached = std::prev(marschnerTables_.end());
            }
            entry.modelAndLayer.y = tableLayer(upload, cached->halfTexels, cached->width, cached->height, 2);
        }
        if (material.dualScattering) {
            // The fibre's layer: the same cache, keyed by what the layer depends on.
            auto cached = std::find_if(dualScatteringTables_.begin(), dualScatteringTables_.end(), [&](const CachedTables& c) {
                return c.material.sharesDualScatteringTableWith(material);
            });
            if (cached == dualScatteringTables_.end()) {
                DualScatteringTable built =
                    buildDualScatteringTable(material.marschner, material.densities.backward, kMarschnerTableHeight);
                dualScatteringTables_.push_back({material, built.halfLayer(kMarschnerTableWidth, kMarschnerTableHeight),
                                                 kMarschnerTableWidth, kMarschnerTableHeight});
                cached = std::prev(dualScatteringTables_.end());
            }
            entry.segments.w = tableLayer(upload, cached->halfTexels, cached->width, cached->height, 1);
            entry.modelAndLayer.z |= gl::kHairMaterialDualScattering;
            entry.caustic.z = material.densities.forward;
            entry.caustic.w = material.densities.backward;
        }
        upload.materials.push_back(entry);
    }
    // Per-point records, prim by prim; a per-point material belongs to one
    // prim, so it records where that prim's control points and records start.
    for (size_t i = 0; i < drawn.size(); ++i) {
        const HairMaterial& material = materials[size_t(drawn[i].material)];
        if (!material.perPoint()) continue;
        gl::GpuHairMaterial& entry = upload.materials[size_t(drawn[i].material)];
        entry.modelAndLayer.z |= gl::kHairMaterialPerPoint;
        entry.modelAndLayer.w = int32_t(upload.parameterPoints.size() / 2);
        entry.segments.x = int32_t(uploads.firstControls[i]);
        const std::vector<glm::vec4>& points = drawnCurves[i]->parameterPoints;
        upload.parameterPoints.insert(upload.parameterPoints.end(), points.begin(), points.end());
    }
    uploadedMaterials_ = materials;
    materialRanges_ = uploads.ranges;
    materialFirstControls_ = uploads.firstControls;
    materialSrbfTables_ = srbfTables;
    return upload;
}

RenderResult Renderer::render(const Scene& scene, const CameraView& camera, const RenderSettings& settings,
                              Diagnostics& diagnostics, const RenderOutputs& outputs, const FrameControl& control) {
    const int factor = settings.values().supersampling;
    if (factor == 1) return renderSamples(scene, camera, settings, diagnostics, outputs, control);
    // The display transform must see the resolved linear pixels: a display
    // image of the samples, averaged, would filter in display space.
    if (outputs.gpuDisplay)
        throw std::invalid_argument(fmt::format("supersampling={} needs the display transform on the CPU "
                                                "(--displayTransformOn cpu): it must follow the box filter",
                                                factor));
    Clock::time_point start = Clock::now();
    RenderOutputs sampleOutputs = outputs;
    sampleOutputs.depth = outputs.depth || outputs.ids;  // the nearest sample chooses the ids
    RenderResult result =
        renderSamples(scene, supersampledCamera(camera, factor), settings, diagnostics, sampleOutputs, control);
    Clock::time_point resolveStart = Clock::now();
    resolveSupersampling(result, factor);
    if (!outputs.depth) result.depth = Image();
    result.stats.passes.push_back({"supersampleResolve", millisecondsSince(resolveStart)});
    result.stats.supersampling = factor;
    result.stats.imageWidth = camera.imageWidth;
    result.stats.imageHeight = camera.imageHeight;
    result.stats.totalMilliseconds = millisecondsSince(start);
    return result;
}

void Renderer::prepareFrame(const Scene& scene, const RenderSettings& settings, Diagnostics& diagnostics,
                            RenderStats& stats) {
    if (!glWarningReported_ && !glThread_->softwareRendererWarning().empty())
        diagnostics.warn("gl", glThread_->softwareRendererWarning());
    glWarningReported_ = true;
    prepareChangedCurves(scene, settings, diagnostics);
    stats.passes.push_back({"prepareCurves", pendingPrepareMilliseconds_});
    stats.preparedPrims = pendingPreparedPrims_;
    pendingPrepareMilliseconds_ = 0.0;
    pendingPreparedPrims_ = 0;
    if (scene.meshes().empty() && meshes_.empty()) return;
    Clock::time_point meshStart = Clock::now();
    prepareMeshes(scene, settings, diagnostics);
    stats.passes.push_back({"prepareMeshes", millisecondsSince(meshStart)});
    stats.preparedMeshes = pendingPreparedMeshes_;
    pendingPreparedMeshes_ = 0;
}

void Renderer::gatherDrawnCurves(const Scene& scene, const CameraView& camera, const RenderSettings& settings,
                                 Diagnostics& diagnostics, GatheredFrame& frame, RenderStats& stats) {
    Diagnostics repeated;  // later instances' material warnings (reportingFor)
    const std::string materialSettings = hairMaterialSettingsKey(settings);
    StrandSummary& summary = frame.strands;
    summary.minProjectedWidthPixels = std::numeric_limits<double>::infinity();
    summary.anyLit = false;
    for (const auto& [path, entry] : scene.curves()) {
        CachedCurves& cached = curves_.at(path);
        if (!entry.prim->visible || cached.prepared->empty()) continue;
        if (!cached.material || cached.materialSettings != materialSettings) {
            cached.material = hairMaterialFor(*entry.prim, *cached.prepared, settings,
                                              reportingFor(*entry.prim, diagnostics, repeated));
            cached.materialSettings = materialSettings;
            cached.parameterPoints = hairParameterPoints(*cached.material, *cached.prepared);
        }
        const HairMaterial& material = *cached.material;
        summary.perPointPrims += material.perPoint() ? 1 : 0;
        summary.analyticPrims += material.analyticAzimuthal ? 1 : 0;
        auto found = std::find(frame.materials.begin(), frame.materials.end(), material);
        if (found == frame.materials.end()) found = frame.materials.insert(frame.materials.end(), material);
        frame.inputs.drawn.push_back({path, cached.prepared, glm::ivec2(entry.prim->primId, entry.prim->instanceId),
                                      int32_t(found - frame.materials.begin())});
        frame.drawnCurves.push_back(&cached);
        summary.anyLit = summary.anyLit || material.model != ShadingModel::Flat;
        if (summary.shadingModels.find(toString(material.model)) == std::string::npos)
            summary.shadingModels += (summary.shadingModels.empty() ? "" : "+") + std::string(toString(material.model));
        summary.segments += cached.prepared->segmentCount();
        summary.allOpaque = summary.allOpaque && cached.fullyOpaque;
        summary.minProjectedWidthPixels =
            std::min(summary.minProjectedWidthPixels,
                     minProjectedWidthPixels(camera, *cached.prepared, cached.minSpanWidth));
        const double primWidth = maxProjectedWidthPixels(camera, *cached.prepared, cached.maxWidth);
        summary.maxProjectedWidthPixels = std::max(summary.maxProjectedWidthPixels, primWidth);
        summary.prims.push_back({primWidth, cached.prepared->segmentCount(),
                                 fragmentsPerSpanEstimate(camera, *cached.prepared, cached.meanSpanLength,
                                                          cached.meanSpanWidth)});
        // Every drawn strand casts shadows.
        summary.casters = unite(summary.casters, CasterBounds{cached.prepared->boundsMin, cached.prepared->boundsMax,
                                                             double(cached.maxWidth)});
        summary.spanLengths.push_back(&cached.spanLengths);
        frame.curves += cached.prepared->curveCount;
        stats.authoredPoints += entry.prim->points.size();
    }
    // Each material's multiple scattering, with the prims that use it (one
    // pass over the prims: a stage may have a material per prim).
    std::vector<size_t> primsOf(frame.materials.size(), 0);
    std::vector<const std::string*> firstOf(frame.materials.size(), nullptr);
    for (const DrawnPrim& drawn : frame.inputs.drawn)
        if (primsOf[size_t(drawn.material)]++ == 0) firstOf[size_t(drawn.material)] = &drawn.path;
    for (size_t m = 0; m < frame.materials.size(); ++m) {
        const HairMaterial& material = frame.materials[m];
        const size_t prims = primsOf[m];
        const std::string first = firstOf[m] ? *firstOf[m] : std::string();
        stats.multipleScattering.push_back({{"material", m},
                                            {"prims", prims},
                                            {"prim", first},
                                            {"model", toString(material.model)},
                                            {"dualScattering", material.dualScattering},
                                            {"gain", material.multipleScatteringGain},
                                            {"reason", material.multipleScatteringReason}});
        summary.dualScatteringMaterials += material.dualScattering ? 1 : 0;
        if (material.model == ShadingModel::Marschner)
            summary.multipleScattering.push_back(fmt::format("{}{}: {}", first, prims > 1 ? fmt::format(" and {} more", prims - 1) : "",
                                                             material.multipleScatteringReason));
    }
}

Renderer::GatheredFrame Renderer::gatherFrame(const Scene& scene, const CameraView& camera,
                                              const RenderSettings& settings, Diagnostics& diagnostics,
                                              const FrameControl& control, RenderStats& stats) {
    GatheredFrame frame;
    FrameInputs& inputs = frame.inputs;
    gatherDrawnCurves(scene, camera, settings, diagnostics, frame, stats);
    inputs.uploads = uploads_.update(inputs.drawn);
    // Any strand written, moved or dropped changes what casts shadows.
    const bool castersChanged =
        std::any_of(inputs.uploads.writes.begin(), inputs.uploads.writes.end(),
                    [](const StrandWrite& write) { return !write.materialOnly; }) ||
        inputs.uploads.drawRanges != castersRanges_;
    if (castersChanged) ++castersVersion_;
    castersRanges_ = inputs.uploads.drawRanges;
    // The domes as lighting (DomeLighting.h): fitted through the fit cache,
    // and the materials' SRBF tables with them.
    frame.domes = frameDomeEnvironments(scene, settings, diagnostics);
    inputs.materials = materialUpload(frame.materials, frame.drawnCurves, inputs.drawn, inputs.uploads,
                                      !frame.domes.empty(), diagnostics);
    inputs.materialFeatures = materialShadingFeatures(frame.materials, !frame.domes.empty());
    for (size_t i = 0; i < inputs.drawn.size(); ++i) {
        const PreparedCurves& curves = *inputs.drawn[i].curves;
        inputs.sortSpans.push_back(SortSpan{curves.controlPoints.data(), curves.segmentFirstControl.data(),
                                            frame.drawnCurves[i]->sortHashes.data(), curves.segmentCount(),
                                            inputs.uploads.ranges[i].first});
    }
    if (control.preview) keepEveryNthCurve(inputs, control.previewCurveStride);
    inputs.meshes = meshUpload(scene, frame.meshes);
    // Meshes occlude the lights too: a changed mesh changes every shadow.
    if (inputs.meshes.changed) ++castersVersion_;
    return frame;
}

std::optional<FrameFallback> Renderer::runFrame(FrameInputs& inputs, RenderResult& result, Diagnostics& diagnostics,
                                                const FrameControl& control) {
    RenderStats& stats = result.stats;
    const ExecutionPlan& execution = result.plan.recipe().execution;
    const DrawBatching drawBatching = execution.batching;
    const gl::PatchBatching batching = drawBatching == DrawBatching::Auto
                                           ? gl::PatchBatching::forDriver(glThread_->contextDescription())
                                           : gl::PatchBatching::forced(drawBatching == DrawBatching::On);
    stats.drawBatching = batching.describe();
    const gl::PassTiming timing = execution.passTimings ? passTiming_ : gl::PassTiming::Off;
    stats.passTiming = gl::toString(timing);
    for (const auto& [path, cached] : curves_) {
        stats.cpuBytes["preparedCurves"] += cached.prepared ? cached.prepared->heldBytes() : 0;
        stats.cpuBytes["sortHashes"] += cached.sortHashes.capacity() * sizeof(uint16_t);
        stats.cpuBytes["spanLengths"] += cached.spanLengths.capacity() * sizeof(float);
        stats.cpuBytes["hairParameterPoints"] += cached.parameterPoints.capacity() * sizeof(glm::vec4);
    }
    std::string failure;
    std::optional<FrameFallback> fallback;
    std::vector<double> passMilliseconds;
    const bool stopped = glThread_->run([&] {
        resources_->strands.setBatching(batching);
        inputs.samples = std::min(result.plan.recipe().transparency.msaaSamples, resources_->maxSamples);
        FrameContext context{inputs, result.plan, *resources_, diagnostics, result, {}, nullptr, false, {}};
        context.cancellation = control.cancellation;
        context.strandPieceSegments = control.strandPieceSegments;
        context.checkAccess = control.checkResourceAccess;
        runFrameGraph(context, timing);
        stats.strandTriangles = resources_->strandPass.takeTriangles();
        const gl::LightViewSpanCounts spans = resources_->shadowMapPass.takeSpanCounts();
        stats.lightViewStraightSpans = spans.straight;
        stats.lightViewTessellatedSpans = spans.tessellated;
        stats.lightViewComputeSpans = spans.compute;
        stats.gpuBytes = gl::gpuBytesByUse();
        stats.cpuBytes["drawOrder"] = context.drawOrder.capacity() * sizeof(uint32_t);
        // A shadow that could not be built, or whose passes a stopped frame
        // skipped, is built again next frame.
        for (const std::string& key : context.unbuiltShadowMaps) shadowMaps_.forget(key);
        failure = context.failure;
        fallback = context.fallback;
        passMilliseconds = std::move(context.passMilliseconds);
        return context.stopped;
    });
    stats.plan = result.plan.toJson(passMilliseconds);
    if (!failure.empty()) throw std::runtime_error(failure);
    if (fallback) {
        result.abandonedPlans.push_back({fallback->reason, result.plan, passMilliseconds});
        return fallback;
    }
    if (stopped) throw FrameCancelled();
    return std::nullopt;
}

void Renderer::reportFrame(const Scene& scene, const CameraView& camera, const RenderSettings& settings,
                           const GatheredFrame& frame, Diagnostics& diagnostics, RenderResult& result) {
    const FrameRecipe& recipe = result.plan.recipe();
    RenderStats& stats = result.stats;
    if (recipe.lighting.overCap > 0)
        diagnostics.warn("render", fmt::format("the stage has {} lights, more than the {} a frame shades; the last {} "
                                               "in path order are left out",
                                               scene.lights().size(), kMaxLights, recipe.lighting.overCap));
    replaceNonFinitePixels(result, diagnostics);
    if (frame.inputs.samples < recipe.transparency.msaaSamples)
        diagnostics.warn("render", fmt::format("msaaSamples={} is more than this GL driver offers; using {}",
                                               recipe.transparency.msaaSamples, frame.inputs.samples));
    stats.lightPasses = recipe.lighting.batches.size();
    stats.uploadedSegments = frame.inputs.uploads.writtenSegments;
    stats.imageWidth = camera.imageWidth;
    stats.imageHeight = camera.imageHeight;
    stats.curvesPrims = scene.curves().size();
    stats.meshPrims = scene.meshes().size();
    stats.lights = scene.lights().size();
    stats.curves = frame.curves;
    stats.segments = frame.strands.segments;
    stats.meshTriangles = frame.meshes.triangles;
    stats.transparency = toString(recipe.transparency.path);
    stats.strandRaster =
        recipe.strandRaster.mixesRasterisers() ? "compute+hardware" : toString(recipe.strandRaster.rasteriser);
    stats.expectedFragments = recipe.strandRaster.expectedFragments;
    stats.glRenderer = glDescription();
    stats.glDevice = glDevice();
    stats.settings = settings.toJson();
    stats.settingOrigins = settingOriginsJson(settings);
    for (const AbandonedPlan& abandoned : result.abandonedPlans)
        stats.abandonedPlans.push_back(
            {{"reason", abandoned.reason}, {"plan", abandoned.plan.toJson(abandoned.passMilliseconds)}});
}

RenderPlan Renderer::planFrame(const Scene& scene, const CameraView& camera, const RenderSettings& settings,
                               const GatheredFrame& frame, const PlanRequest& request, const FrameControl& control,
                               Diagnostics& diagnostics, RenderStats& stats) {
    RenderPlan provisional =
        makeRenderPlan(scene, settings, camera, frame.strands, frame.meshes, frame.domes, request);
    // A preview leaves the shadow maps to the full frames.
    if (control.preview) return provisional;
    PlanRequest withMaps = request;
    withMaps.shadowMaps = decideShadowMaps(provisional, frame.strands, request.fallbacks, diagnostics, stats);
    return makeRenderPlan(scene, settings, camera, frame.strands, frame.meshes, frame.domes, withMaps);
}

RenderResult Renderer::renderSamples(const Scene& scene, const CameraView& camera, const RenderSettings& settings,
                                     Diagnostics& diagnostics, const RenderOutputs& outputs,
                                     const FrameControl& control) {
    Clock::time_point frameStart = Clock::now();
    if (!isFiniteTransform(camera.view) || !isFiniteTransform(camera.projection))
        throw std::invalid_argument("the camera's view or projection is not finite (a NaN or infinite transform, "
                                    "lens or clipping range)");
    checkFrameFitsMemory(camera.imageWidth, camera.imageHeight, settings, outputs.ids, outputs.depth, 0,
                         availableMemory());
    if (control.preview && settings.values().shadowMode != ShadowMode::Off)
        throw std::invalid_argument("a preview frame must not cast shadows (shadowMode=off): it keeps the full "
                                    "frames' shadow maps as they are");
    if (control.previewCurveStride < 1 || (!control.preview && control.previewCurveStride != 1))
        throw std::invalid_argument("only a preview leaves curves out (previewCurveStride 1 otherwise)");
    RenderResult result;
    const size_t warningsBefore = diagnostics.warningCount();
    prepareFrame(scene, settings, diagnostics, result.stats);
    GatheredFrame frame = gatherFrame(scene, camera, settings, diagnostics, control, result.stats);
    FrameInputs& inputs = frame.inputs;
    inputs.camera = &camera;
    inputs.idsRequested = outputs.ids;
    inputs.depthRequested = outputs.depth;
    inputs.gpuDisplay = outputs.gpuDisplay;
    inputs.displayOverBlack = outputs.displayOverBlack;
    PlanRequest request;
    request.idsRequested = outputs.ids;
    request.displayOnGpu = outputs.gpuDisplay != nullptr;
    // Each attempt that a pass finds impossible (FrameFallback.h) is planned
    // again without what it could not do; every fallback is reported once, so
    // there are at most as many attempts as kinds of fallback and lights.
    for (;;) {
        // Warnings about the plan are said once, by the first attempt.
        Diagnostics replanning;
        Diagnostics& planning = result.abandonedPlans.empty() ? diagnostics : replanning;
        result.plan = planFrame(scene, camera, settings, frame, request, control, planning, result.stats);
        const FrameRecipe& recipe = result.plan.recipe();
        inputs.frame = frameUniforms(camera, recipe);
        inputs.fragmentListCapacity = size_t(recipe.transparency.exactMemoryMB) * 1024 * 1024 / gl::kFragmentNodeBytes;
        inputs.computeRasterCapacity = size_t(recipe.strandRaster.memoryMB) * 1024 * 1024 / gl::kFragmentNodeBytes;
        const size_t passesBefore = result.stats.passes.size();
        const std::optional<FrameFallback> fallback = runFrame(inputs, result, diagnostics, control);
        if (!fallback) break;
        if (!request.fallbacks.add(*fallback))
            throw std::logic_error("a frame pass reported a fallback its plan had already made: " + fallback->reason);
        // The abandoned attempt's pass times are its plan's (abandonedPlans);
        // what it sent to the GPU is there for the next attempt.
        result.stats.passes.resize(passesBefore);
        keepUploadsOfAbandonedAttempt(inputs);
    }
    result.stats.fallback = request.fallbacks.describe();
    reportFrame(scene, camera, settings, frame, diagnostics, result);
    result.stats.warnings = diagnostics.warningCount() - warningsBefore;
    result.stats.totalMilliseconds = millisecondsSince(frameStart);
    return result;
}

}  // namespace hdhair
