#include "hdHair/hydra/RenderParam.h"

#include <algorithm>

#include "pxr/base/tf/diagnostic.h"

#include "hdHair/gl/GlContext.h"

PXR_NAMESPACE_OPEN_SCOPE

HdHairRenderParam::HdHairRenderParam() {
    // Repairs made while preparing curves reach the host's log as warnings.
    _diagnostics.setListener([](hdhair::Diagnostic const& warning) {
        TF_WARN("hdHair: %s: %s", warning.where.c_str(), warning.message.c_str());
    });
}

HdHairRenderParam::~HdHairRenderParam() = default;

void HdHairRenderParam::SetCurves(HdRprim const* rprim, hdhair::CurvesPrim prim, int refineLevel) {
    std::lock_guard<std::mutex> lock(_mutex);
    std::string path = prim.path;
    _rprims[path] = Rprim{rprim, refineLevel};
    ++_syncCounts[path];
    _scene.setCurves(std::move(prim));
}

void HdHairRenderParam::SetMesh(HdRprim const* rprim, hdhair::MeshPrim prim) {
    std::lock_guard<std::mutex> lock(_mutex);
    std::string path = prim.path;
    _rprims[path] = Rprim{rprim, 0};
    ++_syncCounts[path];
    _scene.setMesh(std::move(prim));
}

void HdHairRenderParam::SetLight(hdhair::LightPrim light) {
    std::lock_guard<std::mutex> lock(_mutex);
    ++_syncCounts[light.path];
    _scene.setLight(std::move(light));
}

void HdHairRenderParam::Remove(std::string const& path) {
    std::lock_guard<std::mutex> lock(_mutex);
    _rprims.erase(path);
    _scene.remove(path);
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
