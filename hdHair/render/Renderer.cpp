#include "hdHair/render/Renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

#include <fmt/format.h>
#include <glad/gl.h>
#include <glm/geometric.hpp>
#include <tbb/parallel_for.h>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/gl/FragmentListPass.h"
#include "hdHair/gl/GlRenderThread.h"
#include "hdHair/gl/HairMaterialTable.h"
#include "hdHair/gl/LightBatchAccumulation.h"
#include "hdHair/gl/RenderTarget.h"
#include "hdHair/gl/StrandGeometry.h"
#include "hdHair/gl/StrandPass.h"
#include "hdHair/render/BinSort.h"
#include "hdHair/render/NearestStrandRule.h"
#include "hdHair/scene/Scene.h"
#include "hdHair/shading/MarschnerTables.h"

namespace hdhair {
namespace {

using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

glm::dvec3 cameraPositionOf(const CameraView& camera) { return glm::dvec3(glm::inverse(camera.view)[3]); }

glm::dvec3 viewDirectionOf(const CameraView& camera) {
    return glm::normalize(glm::dvec3(glm::inverse(camera.view) * glm::dvec4(0.0, 0.0, -1.0, 0.0)));
}

// Pixels a world unit spans horizontally at clip w = 1: half the image width
// times the projection's x scale (GL matrices: [0][0]).
double pixelsPerUnit(const CameraView& camera) { return camera.projection[0][0] * camera.imageWidth * 0.5; }

gl::FrameUniforms frameUniforms(const CameraView& camera, const RenderSettings& settings, const RenderPlan& plan) {
    gl::FrameUniforms frame;
    frame.viewProjection = glm::mat4(camera.projection * camera.view);
    frame.cameraPosition = glm::vec4(glm::vec3(cameraPositionOf(camera)), camera.orthographic ? 0.0f : 1.0f);
    frame.cameraForward = glm::vec4(glm::vec3(viewDirectionOf(camera)), 0.0f);
    frame.viewportSize = glm::vec2(float(camera.imageWidth), float(camera.imageHeight));
    frame.pixelsPerSegment = float(settings.getFloat("pixelsPerSegment"));
    frame.maxSegmentsPerSpan = float(settings.getInt("maxSegmentsPerSpan"));
    frame.pixelsPerUnit = float(pixelsPerUnit(camera));
    bool opaque = plan.transparency == TransparencyPath::Opaque;
    // The opaque path draws true widths; every blended path applies coverage.
    frame.minPixelWidth = opaque ? 0.0f : float(settings.getFloat("minPixelWidth"));
    frame.drawMode = opaque ? 0 : 1;
    frame.orderedDraw = plan.transparency == TransparencyPath::BinSorted ? 1 : 0;
    frame.nearestStrandMinAlpha = kNearestStrandMinAlpha;
    return frame;
}

// The lights of one batch; the dome's ambient term belongs to the first
// batch only, so that summing batches counts it once.
gl::LightUniforms lightUniforms(const RenderPlan& plan, size_t batch) {
    gl::LightUniforms uniforms;
    auto [begin, end] = plan.lightBatches[batch];
    size_t count = end - begin;
    for (size_t i = 0; i < count; ++i) {
        const ShadingLight& light = plan.lights.lights[begin + i];
        uniforms.lightVector[i] = glm::vec4(light.directionOrPosition, light.isLocal ? 1.0f : 0.0f);
        uniforms.lightScale[i] = glm::vec4(light.scale, 0.0f);
        uniforms.lightAxis[i] = glm::vec4(light.emissionAxis, light.oneSided ? 1.0f : 0.0f);
        uniforms.lightCone[i] = glm::vec4(light.coneCosOuter, light.coneCosInner, light.shaped ? 1.0f : 0.0f, 0.0f);
    }
    uniforms.lightCount = glm::ivec4(int(count), 0, 0, 0);
    uniforms.ambient = glm::vec4(batch == 0 ? plan.lights.ambient : glm::vec3(0.0f), 0.0f);
    return uniforms;
}

// The thinnest projected width of any strand: its thinnest span end at the
// farthest depth of its bounds (a lower bound for perspective cameras).
double minProjectedWidthPixels(const CameraView& camera, const PreparedCurves& curves, float minSpanWidth) {
    double farthest = 0.0;
    if (!camera.orthographic) {
        for (int corner = 0; corner < 8; ++corner) {
            glm::dvec3 p((corner & 1) ? curves.boundsMax.x : curves.boundsMin.x,
                         (corner & 2) ? curves.boundsMax.y : curves.boundsMin.y,
                         (corner & 4) ? curves.boundsMax.z : curves.boundsMin.z);
            farthest = std::max(farthest, (camera.projection * camera.view * glm::dvec4(p, 1.0)).w);
        }
        if (farthest <= 0.0) return std::numeric_limits<double>::infinity();  // behind the camera
    } else {
        farthest = 1.0;
    }
    return double(minSpanWidth) * pixelsPerUnit(camera) / farthest;
}

// The instances of an instanced prim are copies of its first instance but for
// the transform (HdHairRenderParam::SetCurves), so whatever their data needs
// repaired is the first instance's again: only the first reports it, and a
// PointInstancer of 10,000 strands warns once, not 10,000 times.
Diagnostics& reportingFor(const CurvesPrim& prim, Diagnostics& diagnostics, Diagnostics& repeated) {
    return prim.instanceId == 0 ? diagnostics : repeated;
}

}  // namespace

Renderer::Renderer(gl::GlBackend backend) : glThread_(std::make_unique<gl::GlRenderThread>(backend)) {
    glThread_->run([this] {
        strandPass_ = std::make_unique<gl::StrandPass>();
        fragmentListPass_ = std::make_unique<gl::FragmentListPass>();
        lightBatchAccumulation_ = std::make_unique<gl::LightBatchAccumulation>();
        materialTable_ = std::make_unique<gl::HairMaterialTable>();
        glGetIntegerv(GL_MAX_SAMPLES, &maxSamples_);
    });
}

Renderer::~Renderer() {
    // GL objects die on the thread that owns the context.
    glThread_->run([this] {
        geometry_.reset();
        strandPass_.reset();
        fragmentListPass_.reset();
        lightBatchAccumulation_.reset();
        materialTable_.reset();
        target_.reset();
        batchTarget_.reset();
    });
}

const std::string& Renderer::glDescription() const { return glThread_->contextDescription(); }

SceneBounds Renderer::prepare(const Scene& scene, Diagnostics& diagnostics) {
    Clock::time_point start = Clock::now();
    for (auto it = curves_.begin(); it != curves_.end();)
        it = scene.curves().count(it->first) ? std::next(it) : curves_.erase(it);
    // Meshes count for framing but are not drawn: say so once per mesh, the
    // first time it is visible, whichever reader brought it.
    for (auto it = reportedMeshes_.begin(); it != reportedMeshes_.end();)
        it = scene.meshes().count(*it) ? std::next(it) : reportedMeshes_.erase(it);
    for (const auto& [path, entry] : scene.meshes()) {
        if (entry.prim->visible && reportedMeshes_.insert(path).second)
            diagnostics.warn(path, "mesh not drawn: hdHair draws curves only (meshes as occluders are not "
                                   "implemented yet)");
    }
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
        if (cached.prepared && cached.version == entry.version && cached.colorMaterialVersion == materialVersion)
            continue;
        cached.version = entry.version;
        cached.colorMaterialVersion = materialVersion;
        changed.push_back({entry.prim.get(), material ? material->prim.get() : nullptr, &cached});
    }
    Diagnostics repeated;  // later instances' repairs (reportingFor)
    tbb::parallel_for(size_t(0), changed.size(), [&](size_t i) {
        Diagnostics& report = reportingFor(*changed[i].prim, diagnostics, repeated);
        const StrandColorSource colors = strandColorSource(*changed[i].prim, changed[i].material, report);
        auto prepared = std::make_shared<PreparedCurves>(
            prepareCurves(*changed[i].prim, report, hairParameterPrimvars(), &colors));
        CachedCurves& cached = *changed[i].cached;
        cached.minSpanWidth = std::numeric_limits<float>::max();
        cached.fullyOpaque = true;
        for (size_t c = 0; c < prepared->controlPoints.size(); ++c) {
            const StrandControlPoint& point = prepared->controlPoints[c];
            cached.fullyOpaque = cached.fullyOpaque && point.opacity == 1.0f;
            if (c % 4 == 1 || c % 4 == 2) cached.minSpanWidth = std::min(cached.minSpanWidth, point.width);
        }
        cached.prepared = std::move(prepared);
        cached.material.reset();
        cached.parameterPoints.clear();
    });
    pendingPrepareMilliseconds_ += millisecondsSince(start);

    SceneBounds bounds;
    auto include = [&](const glm::dvec3& low, const glm::dvec3& high) {
        bool first = bounds.empty();
        bounds.min = first ? low : glm::min(bounds.min, low);
        bounds.max = first ? high : glm::max(bounds.max, high);
    };
    for (const auto& [path, entry] : scene.curves()) {
        const CachedCurves& cached = curves_.at(path);
        if (!entry.prim->visible || cached.prepared->empty()) continue;
        include(glm::dvec3(cached.prepared->boundsMin), glm::dvec3(cached.prepared->boundsMax));
    }
    for (const auto& [path, entry] : scene.meshes()) {
        if (!entry.prim->visible) continue;
        for (const glm::vec3& point : entry.prim->points) {
            glm::dvec3 world = glm::dvec3(entry.prim->worldTransform * glm::dvec4(glm::dvec3(point), 1.0));
            if (std::isfinite(world.x) && std::isfinite(world.y) && std::isfinite(world.z)) include(world, world);
        }
    }
    return bounds;
}

void Renderer::updateGeometry(const std::vector<VisiblePrim>& visible, const std::vector<uint64_t>& key,
                              RenderStats& stats) {
    if (geometry_ && key == geometryKey_) return;
    Clock::time_point start = Clock::now();
    size_t segments = 0;
    for (const VisiblePrim& prim : visible) segments += prim.cached->prepared->segmentCount();
    controlPoints_.clear();
    controlPoints_.reserve(4 * segments);
    std::vector<int32_t> segmentCurves, segmentMaterials;
    std::vector<glm::ivec2> segmentPrims;
    segmentCurves.reserve(segments);
    segmentPrims.reserve(segments);
    segmentMaterials.reserve(segments);
    for (const VisiblePrim& prim : visible) {
        const PreparedCurves& prepared = *prim.cached->prepared;
        controlPoints_.insert(controlPoints_.end(), prepared.controlPoints.begin(), prepared.controlPoints.end());
        for (uint32_t curve : prepared.segmentCurve) {
            segmentCurves.push_back(int32_t(curve));
            segmentPrims.emplace_back(prim.primId, prim.instanceId);
            segmentMaterials.push_back(prim.material);
        }
    }
    glThread_->run([&] {
        geometry_ = std::make_unique<gl::StrandGeometry>(controlPoints_, segmentCurves, segmentPrims, segmentMaterials);
        glFinish();
    });
    geometryKey_ = key;
    stats.passes.push_back({"upload", millisecondsSince(start)});
}

void Renderer::updateMaterials(const std::vector<HairMaterial>& materials, const std::vector<VisiblePrim>& visible) {
    if (materials == uploadedMaterials_ && geometryKey_ == materialsGeometryKey_) return;
    std::vector<gl::GpuHairMaterial> gpu;
    std::vector<glm::vec4> parameterPoints;
    std::vector<const std::vector<uint16_t>*> tables;
    int width = 1, height = 1;
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
            width = cached->width;
            height = cached->height;
            auto layer = std::find(tables.begin(), tables.end(), &cached->halfTexels);
            if (layer == tables.end()) layer = tables.insert(tables.end(), &cached->halfTexels);
            entry.modelAndLayer.y = int(2 * (layer - tables.begin()));
        }
        gpu.push_back(entry);
    }
    // Per-point records, prim by prim; a per-point material belongs to one
    // prim, so it records where that prim's segments and records start.
    int32_t firstSegment = 0;
    for (const VisiblePrim& prim : visible) {
        const HairMaterial& material = materials[size_t(prim.material)];
        if (material.perPoint()) {
            gl::GpuHairMaterial& entry = gpu[size_t(prim.material)];
            entry.modelAndLayer.z |= gl::kHairMaterialPerPoint;
            entry.modelAndLayer.w = int32_t(parameterPoints.size() / 2);
            entry.segments.x = firstSegment;
            const std::vector<glm::vec4>& points = prim.cached->parameterPoints;
            parameterPoints.insert(parameterPoints.end(), points.begin(), points.end());
        }
        firstSegment += int32_t(prim.cached->prepared->segmentCount());
    }
    glThread_->run([&] { materialTable_->update(gpu, parameterPoints, tables, width, height); });
    uploadedMaterials_ = materials;
    materialsGeometryKey_ = geometryKey_;
}

RenderResult Renderer::render(const Scene& scene, const CameraView& camera, const RenderSettings& settings,
                              Diagnostics& diagnostics, const RenderOutputs& outputs) {
    Clock::time_point frameStart = Clock::now();
    RenderResult result;
    RenderStats& stats = result.stats;
    size_t warningsBefore = diagnostics.warningCount();
    prepare(scene, diagnostics);
    stats.passes.push_back({"prepareCurves", pendingPrepareMilliseconds_});
    pendingPrepareMilliseconds_ = 0.0;

    std::vector<VisiblePrim> visible;
    Diagnostics repeated;  // later instances' material warnings (reportingFor)
    const std::string materialSettings = hairMaterialSettingsKey(settings);
    std::vector<uint64_t> geometryKey;  // versions, then material indices
    std::vector<HairMaterial> materials;
    StrandSummary summary;
    summary.minProjectedWidthPixels = std::numeric_limits<double>::infinity();
    summary.anyLit = false;
    uint64_t curveCount = 0;
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
        auto found = std::find(materials.begin(), materials.end(), material);
        if (found == materials.end()) found = materials.insert(materials.end(), material);
        int materialIndex = int(found - materials.begin());
        visible.push_back({entry.prim->primId, entry.prim->instanceId, &cached, materialIndex});
        geometryKey.push_back(cached.version);
        geometryKey.push_back(cached.colorMaterialVersion);
        geometryKey.push_back(uint64_t(materialIndex));
        summary.anyLit = summary.anyLit || material.model != ShadingModel::Flat;
        if (summary.shadingModels.find(toString(material.model)) == std::string::npos)
            summary.shadingModels += (summary.shadingModels.empty() ? "" : "+") + std::string(toString(material.model));
        summary.segments += cached.prepared->segmentCount();
        summary.allOpaque = summary.allOpaque && cached.fullyOpaque;
        summary.minProjectedWidthPixels =
            std::min(summary.minProjectedWidthPixels,
                     minProjectedWidthPixels(camera, *cached.prepared, cached.minSpanWidth));
        curveCount += cached.prepared->curveCount;
    }
    updateGeometry(visible, geometryKey, stats);
    updateMaterials(materials, visible);
    result.plan = makeRenderPlan(scene, settings, camera, summary, outputs.ids);
    RenderPlan& plan = result.plan;

    std::vector<uint32_t> order;
    if (plan.isEnabled("sort")) {
        Clock::time_point sortStart = Clock::now();
        binSortSegments(controlPoints_, cameraPositionOf(camera), viewDirectionOf(camera), plan.sortBins, order);
        stats.passes.push_back({"sort", millisecondsSince(sortStart)});
    }
    gl::FrameUniforms frame = frameUniforms(camera, settings, plan);
    int samples = std::min(plan.msaaSamples, maxSamples_);
    if (samples < plan.msaaSamples)
        diagnostics.warn("render", fmt::format("msaaSamples={} is more than this GL driver offers; using {}",
                                               plan.msaaSamples, samples));
    const size_t listCapacity = size_t(settings.getInt("exactMemoryMB")) * 1024 * 1024 / gl::kFragmentNodeBytes;

    // Blended frames take their depth from the strand pass's min-blended
    // nearest depth (or the exact resolve), not from the depth buffer.
    const gl::RenderTargetImages frameImages{outputs.ids, plan.transparency != TransparencyPath::Opaque, samples};
    // Later light batches add colour only.
    const gl::RenderTargetImages batchImages{false, false, samples};

    glThread_->run([&] {
        if (!target_ || target_->width() != camera.imageWidth || target_->height() != camera.imageHeight ||
            target_->images() != frameImages)
            target_ = std::make_unique<gl::RenderTarget>(camera.imageWidth, camera.imageHeight, frameImages);
        materialTable_->bind();

        // Draws the strands once, with the current plan, into `target`.
        auto drawStrands = [&](gl::RenderTarget& target, const gl::LightUniforms& lights, const std::string& label) {
            Clock::time_point passStart = Clock::now();
            // Empty pixels are transparent black: pre-multiplied "nothing".
            target.bindAndClear(glm::vec4(0.0f));
            strandPass_->setUniforms(frame, lights);
            if (plan.transparency == TransparencyPath::Exact) {
                uint64_t fragments = fragmentListPass_->render(*geometry_, camera.imageWidth, camera.imageHeight,
                                                               listCapacity, frame.maxSegmentsPerSpan);
                glFinish();
                stats.passes.push_back({"strands (exact)" + label, millisecondsSince(passStart)});
                stats.fragments = fragments;
                if (fragments <= listCapacity) return;
                // Over budget: the lists lost fragments, so the image is not
                // exact. Say so and fall back to the finest bin sort (for this
                // batch and the ones after it).
                diagnostics.warn("render", fmt::format("exact transparency needs {} MB for {} fragments, more than "
                                                       "exactMemoryMB={}; rendered with binSorted (1024 bins) instead",
                                                       (fragments * gl::kFragmentNodeBytes + (1 << 20) - 1) >> 20,
                                                       fragments, settings.getInt("exactMemoryMB")));
                plan.fallBackToBinSorted(1024, outputs.ids);
                stats.fallback = "exact -> binSorted (1024 bins): fragment lists over exactMemoryMB";
                binSortSegments(controlPoints_, cameraPositionOf(camera), viewDirectionOf(camera), plan.sortBins, order);
                frame.orderedDraw = 1;
                target.bindAndClear(glm::vec4(0.0f));
                strandPass_->setUniforms(frame, lights);
                passStart = Clock::now();
            }
            strandPass_->draw(*geometry_, order,
                              plan.transparency == TransparencyPath::Opaque ? gl::StrandBlending::Opaque
                                                                            : gl::StrandBlending::PremultipliedOver);
            glFinish();
            stats.passes.push_back({std::string("strands (") + toString(plan.transparency) + ")" +
                                        (stats.fallback.empty() ? "" : " fallback") + label,
                                    millisecondsSince(passStart)});
        };
        auto batchLabel = [&](size_t batch) {
            if (plan.lightBatches.size() == 1) return std::string();
            return fmt::format(" lights {}-{}", plan.lightBatches[batch].first + 1, plan.lightBatches[batch].second);
        };

        if (!plan.isEnabled("strands")) {
            target_->bindAndClear(glm::vec4(0.0f));
        } else {
            drawStrands(*target_, lightUniforms(plan, 0), batchLabel(0));
        }
        if (plan.isEnabled("ids")) {
            Clock::time_point passStart = Clock::now();
            gl::FrameUniforms idsFrame = frame;
            idsFrame.drawMode = 2;
            idsFrame.orderedDraw = 0;
            strandPass_->setUniforms(idsFrame, lightUniforms(plan, 0));
            strandPass_->draw(*geometry_, {}, gl::StrandBlending::IdsOnly);
            glFinish();
            stats.passes.push_back({"ids", millisecondsSince(passStart)});
        }
        target_->resolve();
        if (plan.isEnabled("lightBatches")) {
            if (!batchTarget_ || batchTarget_->width() != camera.imageWidth ||
                batchTarget_->height() != camera.imageHeight || batchTarget_->images() != batchImages)
                batchTarget_ = std::make_unique<gl::RenderTarget>(camera.imageWidth, camera.imageHeight, batchImages);
            for (size_t batch = 1; batch < plan.lightBatches.size(); ++batch) {
                drawStrands(*batchTarget_, lightUniforms(plan, batch), batchLabel(batch));
                Clock::time_point addStart = Clock::now();
                batchTarget_->resolve();
                lightBatchAccumulation_->add(*target_, *batchTarget_);
                glFinish();
                stats.passes.push_back({"accumulate" + batchLabel(batch), millisecondsSince(addStart)});
            }
        }

        Clock::time_point readStart = Clock::now();
        result.color = Image(camera.imageWidth, camera.imageHeight, 4);
        result.color.pixels = target_->readColor();
        result.depth = Image(camera.imageWidth, camera.imageHeight, 1);
        result.depth.pixels = target_->readDepth();
        if (outputs.ids) {
            result.primIds = target_->readIds(0);
            result.instanceIds = target_->readIds(1);
            result.elementIds = target_->readIds(2);
        }
        stats.passes.push_back({"readback", millisecondsSince(readStart)});
    });
    stats.lightPasses = plan.lightBatches.size();

    stats.imageWidth = camera.imageWidth;
    stats.imageHeight = camera.imageHeight;
    stats.curvesPrims = scene.curves().size();
    stats.meshPrims = scene.meshes().size();
    stats.lights = scene.lights().size();
    stats.curves = curveCount;
    stats.segments = summary.segments;
    stats.transparency = toString(plan.transparency);
    stats.glRenderer = glDescription();
    stats.settings = settings.toJson();
    stats.plan = plan.toJson();
    stats.warnings = diagnostics.warningCount() - warningsBefore;
    stats.totalMilliseconds = millisecondsSince(frameStart);
    return result;
}

}  // namespace hdhair
