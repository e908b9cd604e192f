#include "hdHair/hydra/RenderParam.h"

#include <algorithm>

#include "pxr/base/tf/diagnostic.h"

#include "hdHair/gl/GlContext.h"
#include "hdHair/scene/SceneValidation.h"

PXR_NAMESPACE_OPEN_SCOPE

HdHairRenderParam::HdHairRenderParam() {
    // Repairs made while preparing curves reach the host's log as warnings.
    _diagnostics.setListener([](hdhair::Diagnostic const& warning) {
        TF_WARN("hdHair: %s: %s", warning.where.c_str(), warning.message.c_str());
    });
}

HdHairRenderParam::~HdHairRenderParam() = default;

std::string HdHairRenderParam::InstancePath(std::string const& path, size_t instance) {
    return path + "{" + std::to_string(instance) + "}";
}

void HdHairRenderParam::SetCurves(HdRprim const* rprim, hdhair::CurvesPrim prim, int refineLevel,
                                  std::optional<std::vector<glm::dmat4>> const& instanceTransforms) {
    _SetInstanced(rprim, std::move(prim), refineLevel, instanceTransforms, &hdhair::Scene::setCurves);
}

void HdHairRenderParam::SetMesh(HdRprim const* rprim, hdhair::MeshPrim prim,
                                std::optional<std::vector<glm::dmat4>> const& instanceTransforms) {
    const int refineLevel = std::max(prim.refineLevel, 0);
    _SetInstanced(rprim, std::move(prim), refineLevel, instanceTransforms, &hdhair::Scene::setMesh);
}

template <typename Prim>
void HdHairRenderParam::_SetInstanced(HdRprim const* rprim, Prim prim, int refineLevel,
                                      std::optional<std::vector<glm::dmat4>> const& instanceTransforms,
                                      void (hdhair::Scene::*set)(Prim)) {
    std::string const path = prim.path;
    // The instances' copies are made before locking: prims sync in
    // parallel, and a large groom's points take a while to copy.
    std::vector<Prim> instances;
    if (instanceTransforms) {
        instances.reserve(instanceTransforms->size());
        for (size_t i = 0; i < instanceTransforms->size(); ++i) {
            Prim& instance = instances.emplace_back(prim);
            instance.path = InstancePath(path, i);
            instance.worldTransform = (*instanceTransforms)[i];
            instance.instanceId = int(i);
        }
    }
    std::lock_guard<std::mutex> lock(_mutex);
    ++_syncCounts[path];
    _RemoveEnginePrims(path);
    if (!instanceTransforms) {
        _rprims[path] = Rprim{rprim, refineLevel};
        (_scene.*set)(std::move(prim));
        return;
    }
    std::vector<std::string>& paths = _instancePaths[path];
    for (Prim& instance : instances) {
        paths.push_back(instance.path);
        _rprims[instance.path] = Rprim{rprim, refineLevel};
        (_scene.*set)(std::move(instance));
    }
}

void HdHairRenderParam::_RemoveEnginePrims(std::string const& path) {
    auto instances = _instancePaths.find(path);
    if (instances != _instancePaths.end()) {
        for (std::string const& instancePath : instances->second) {
            _rprims.erase(instancePath);
            _scene.remove(instancePath);
        }
        _instancePaths.erase(instances);
    }
    _rprims.erase(path);
    _scene.remove(path);
}

void HdHairRenderParam::SetLight(hdhair::LightPrim light) {
    std::lock_guard<std::mutex> lock(_mutex);
    ++_syncCounts[light.path];
    // The same checks as the embedded reader's (SceneValidation.h); a light
    // that cannot be used leaves the scene.
    if (hdhair::repairLight(light, light.path, _diagnostics))
        _scene.setLight(std::move(light));
    else
        _scene.remove(light.path);
}

void HdHairRenderParam::SetMaterial(hdhair::MaterialPrim material) {
    std::lock_guard<std::mutex> lock(_mutex);
    ++_syncCounts[material.path];
    _scene.setMaterial(std::move(material));
}

void HdHairRenderParam::Remove(std::string const& path) {
    std::lock_guard<std::mutex> lock(_mutex);
    _RemoveEnginePrims(path);
}

hdhair::Scene HdHairRenderParam::Snapshot(TfTokenVector const& renderTags, int* maxRefineLevel) const {
    std::lock_guard<std::mutex> lock(_mutex);
    int refineLevel = 0;
    hdhair::Scene snapshot = _scene.subset([&](std::string const& path) {
        auto rprim = _rprims.find(path);
        if (rprim == _rprims.end()) return true;  // lights and cameras
        // The render tag is read now, after sync: the render index updates
        // it without necessarily syncing the prim again.
        TfToken tag = rprim->second.rprim->GetRenderTag();
        bool drawn = renderTags.empty() ||
                     std::find(renderTags.begin(), renderTags.end(), tag) != renderTags.end();
        if (drawn) refineLevel = std::max(refineLevel, rprim->second.refineLevel);
        return drawn;
    });
    if (maxRefineLevel) *maxRefineLevel = refineLevel;
    return snapshot;
}

uint64_t HdHairRenderParam::GetSceneVersion() const {
    std::lock_guard<std::mutex> lock(_mutex);
    return _scene.version();
}

hdhair::Renderer& HdHairRenderParam::GetRenderer() {
    std::lock_guard<std::mutex> lock(_rendererMutex);
    if (!_renderer) _renderer = std::make_unique<hdhair::Renderer>(hdhair::gl::defaultGlBackend());
    return *_renderer;
}

void HdHairRenderParam::SetLastFrame(std::string statsJson, std::string plan) {
    std::lock_guard<std::mutex> lock(_mutex);
    _lastFrameStats = std::move(statsJson);
    _lastFramePlan = std::move(plan);
}

std::pair<std::string, std::string> HdHairRenderParam::GetLastFrame() const {
    std::lock_guard<std::mutex> lock(_mutex);
    return {_lastFrameStats, _lastFramePlan};
}

void HdHairRenderParam::SetProgress(Progress progress) {
    std::lock_guard<std::mutex> lock(_mutex);
    _progress = std::move(progress);
}

HdHairRenderParam::Progress HdHairRenderParam::GetProgress() const {
    std::lock_guard<std::mutex> lock(_mutex);
    return _progress;
}

size_t HdHairRenderParam::GetSyncCount(std::string const& path) const {
    std::lock_guard<std::mutex> lock(_mutex);
    auto it = _syncCounts.find(path);
    return it == _syncCounts.end() ? 0 : it->second;
}

std::map<std::string, size_t> HdHairRenderParam::GetSyncCounts() const {
    std::lock_guard<std::mutex> lock(_mutex);
    return _syncCounts;
}

PXR_NAMESPACE_CLOSE_SCOPE
