#include "hdHair/render/Renderer.h"

#include <chrono>
#include <cmath>
#include <vector>

#include <glad/gl.h>
#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <tbb/parallel_for.h>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/curves/PreparedCurves.h"
#include "hdHair/gl/GlRenderThread.h"
#include "hdHair/gl/RenderTarget.h"
#include "hdHair/gl/StrandPass.h"
#include "hdHair/scene/Scene.h"
#include "hdHair/shading/KajiyaKay.h"

namespace hdhair {
namespace {

using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

gl::FrameUniforms frameUniforms(const CameraView& camera, const RenderSettings& settings) {
    gl::FrameUniforms frame;
    frame.viewProjection = glm::mat4(camera.projection * camera.view);
    glm::dmat4 cameraToWorld = glm::inverse(camera.view);
    glm::dvec3 forward = glm::normalize(glm::dvec3(cameraToWorld * glm::dvec4(0.0, 0.0, -1.0, 0.0)));
    frame.cameraPosition = glm::vec4(glm::vec3(cameraToWorld[3]), camera.orthographic ? 0.0f : 1.0f);
    frame.cameraForward = glm::vec4(glm::vec3(forward), 0.0f);
    frame.viewportSize = glm::vec2(float(camera.imageWidth), float(camera.imageHeight));
    frame.pixelsPerSegment = float(settings.getFloat("pixelsPerSegment"));
    frame.maxSegmentsPerSpan = float(settings.getInt("maxSegmentsPerSpan"));
    return frame;
}

gl::LightUniforms lightUniforms(const RenderPlan& plan, const RenderSettings& settings,
                                Diagnostics& diagnostics) {
    gl::LightUniforms uniforms;
    size_t count = plan.lights.lights.size();
    if (count > size_t(gl::kMaxLightsPerPass)) {
        diagnostics.warn("render", "the stage has " + std::to_string(count) + " lights; only the first " +
                                       std::to_string(gl::kMaxLightsPerPass) +
                                       " are used until lights are batched over several passes");
        count = size_t(gl::kMaxLightsPerPass);
    }
    for (size_t i = 0; i < count; ++i) {
        const ShadingLight& light = plan.lights.lights[i];
        uniforms.lightVector[i] = glm::vec4(light.directionOrPosition, light.isLocal ? 1.0f : 0.0f);
        uniforms.lightScale[i] = glm::vec4(light.scale, 0.0f);
        uniforms.lightAxis[i] = glm::vec4(light.emissionAxis, light.oneSided ? 1.0f : 0.0f);
    }
    uniforms.lightCount = glm::ivec4(int(count), 0, 0, 0);
    uniforms.ambient = glm::vec4(plan.lights.ambient, 0.0f);
    KajiyaKayParameters kk{float(settings.getFloat("kajiyaKay:diffuse")),
                           float(settings.getFloat("kajiyaKay:specular")),
                           float(settings.getFloat("kajiyaKay:shininess"))};
    uniforms.kajiyaKayParameters = glm::vec4(kk.diffuse, kk.specular, kk.shininess, 0.0f);
    return uniforms;
}

}  // namespace

Renderer::Renderer(gl::GlBackend backend) : glThread_(std::make_unique<gl::GlRenderThread>(backend)) {
    glThread_->run([this] { strandPass_ = std::make_unique<gl::StrandPass>(); });
}

Renderer::~Renderer() {
    // GL objects die on the thread that owns the context.
    glThread_->run([this] {
        for (auto& [path, cached] : curves_) cached.buffer.reset();
        strandPass_.reset();
        target_.reset();
    });
}

const std::string& Renderer::glDescription() const { return glThread_->contextDescription(); }

SceneBounds Renderer::prepare(const Scene& scene, Diagnostics& diagnostics) {
    Clock::time_point start = Clock::now();
    // Drop prims that left the scene (their GPU buffers go with them below).
    std::vector<std::string> removed;
    for (const auto& [path, cached] : curves_)
        if (!scene.curves().count(path)) removed.push_back(path);
    if (!removed.empty()) {
        glThread_->run([&] {
            for (const std::string& path : removed) curves_.erase(path);
        });
    }
    // Prepare changed prims in parallel: curve preparation is CPU work
    // without GL, thread-safe across prims.
    std::vector<std::pair<const CurvesPrim*, CachedCurves*>> changed;
    for (const auto& [path, entry] : scene.curves()) {
        CachedCurves& cached = curves_[path];
        if (cached.prepared && cached.version == entry.version) continue;
        cached.version = entry.version;
        changed.emplace_back(entry.prim.get(), &cached);
    }
    tbb::parallel_for(size_t(0), changed.size(), [&](size_t i) {
        auto prepared = std::make_shared<PreparedCurves>(prepareCurves(*changed[i].first, diagnostics));
        changed[i].second->prepared = std::move(prepared);
    });
    if (!changed.empty()) {
        glThread_->run([&] {
            for (auto& [prim, cached] : changed) cached->buffer.reset();
        });
    }
    pendingPrepareMilliseconds_ += millisecondsSince(start);

    SceneBounds bounds;
    for (const auto& [path, entry] : scene.curves()) {
        const CachedCurves& cached = curves_.at(path);
        if (!entry.prim->visible || cached.prepared->empty()) continue;
        bounds.min = glm::min(bounds.min.x > bounds.max.x ? glm::dvec3(cached.prepared->boundsMin) : bounds.min,
                              glm::dvec3(cached.prepared->boundsMin));
        bounds.max = glm::max(bounds.min.x > bounds.max.x ? glm::dvec3(cached.prepared->boundsMax) : bounds.max,
                              glm::dvec3(cached.prepared->boundsMax));
    }
    for (const auto& [path, entry] : scene.meshes()) {
        if (!entry.prim->visible) continue;
        for (const glm::vec3& point : entry.prim->points) {
            glm::dvec3 world = glm::dvec3(entry.prim->worldTransform * glm::dvec4(glm::dvec3(point), 1.0));
            if (!std::isfinite(world.x) || !std::isfinite(world.y) || !std::isfinite(world.z)) continue;
            bool first = bounds.empty();
            bounds.min = first ? world : glm::min(bounds.min, world);
            bounds.max = first ? world : glm::max(bounds.max, world);
        }
    }
    return bounds;
}

RenderResult Renderer::render(const Scene& scene, const CameraView& camera, const RenderSettings& settings,
                              Diagnostics& diagnostics, const RenderOutputs& outputs) {
    Clock::time_point frameStart = Clock::now();
    RenderResult result;
    size_t warningsBefore = diagnostics.warningCount();
    prepare(scene, diagnostics);
    result.stats.passes.push_back({"prepareCurves", pendingPrepareMilliseconds_});
    pendingPrepareMilliseconds_ = 0.0;

    std::vector<std::pair<int, CachedCurves*>> visible;  // prim id, cached data
    uint64_t segments = 0, curveCount = 0;
    for (const auto& [path, entry] : scene.curves()) {
        CachedCurves& cached = curves_.at(path);
        if (!entry.prim->visible || cached.prepared->empty()) continue;
        visible.emplace_back(entry.prim->primId, &cached);
        segments += cached.prepared->segmentCount();
        curveCount += cached.prepared->curveCount;
    }
    result.plan = makeRenderPlan(scene, settings, camera, segments);
    gl::FrameUniforms frame = frameUniforms(camera, settings);
    gl::LightUniforms lights = lightUniforms(result.plan, settings, diagnostics);

    glThread_->run([&] {
        Clock::time_point uploadStart = Clock::now();
        for (auto& [primId, cached] : visible)
            if (!cached->buffer) cached->buffer = std::make_unique<gl::StrandBuffer>(*cached->prepared);
        glFinish();
        result.stats.passes.push_back({"upload", millisecondsSince(uploadStart)});

        if (!target_ || target_->width() != camera.imageWidth || target_->height() != camera.imageHeight ||
            target_->hasIds() != outputs.ids)
            target_ = std::make_unique<gl::RenderTarget>(camera.imageWidth, camera.imageHeight, outputs.ids);
        // Empty pixels are transparent black: pre-multiplied "nothing".
        target_->bindAndClear(glm::vec4(0.0f));

        if (result.plan.isEnabled("strands")) {
            Clock::time_point passStart = Clock::now();
            std::vector<gl::StrandDraw> draws;
            for (auto& [primId, cached] : visible) draws.push_back({cached->buffer.get(), primId});
            strandPass_->draw(frame, lights, draws);
            glFinish();
            result.stats.passes.push_back({"strands", millisecondsSince(passStart)});
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
        result.stats.passes.push_back({"readback", millisecondsSince(readStart)});
    });

    RenderStats& stats = result.stats;
    stats.imageWidth = camera.imageWidth;
    stats.imageHeight = camera.imageHeight;
    stats.curvesPrims = scene.curves().size();
    stats.meshPrims = scene.meshes().size();
    stats.lights = scene.lights().size();
    stats.curves = curveCount;
    stats.segments = segments;
    stats.glRenderer = glDescription();
    stats.settings = settings.toJson();
    stats.plan = result.plan.toJson();
    stats.warnings = diagnostics.warningCount() - warningsBefore;
    stats.totalMilliseconds = millisecondsSince(frameStart);
    return result;
}

}  // namespace hdhair
