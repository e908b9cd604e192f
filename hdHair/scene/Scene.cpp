#include "hdHair/scene/Scene.h"

#include <atomic>

namespace hdhair {

namespace {

uint64_t nextVersion() {
    static std::atomic<uint64_t> counter{0};
    return ++counter;
}

}  // namespace

template <typename Prim>
void Scene::set(Entries<Prim>& entries, Prim prim) {
    // A path names one prim: drop any prim of another kind at the same path.
    std::string path = prim.path;
    if (!entries.count(path)) remove(path);
    SceneEntry<Prim>& entry = entries[path];
    if (entry.prim && *entry.prim == prim) return;  // unchanged: keeps its version and every cache of it
    entry.prim = std::make_shared<const Prim>(std::move(prim));
    entry.version = version_ = nextVersion();
}

void Scene::setCurves(CurvesPrim prim) { set(curves_, std::move(prim)); }
void Scene::setMesh(MeshPrim prim) { set(meshes_, std::move(prim)); }
void Scene::setCamera(CameraPrim prim) { set(cameras_, std::move(prim)); }
void Scene::setLight(LightPrim prim) { set(lights_, std::move(prim)); }
void Scene::setMaterial(MaterialPrim prim) { set(materials_, std::move(prim)); }

bool Scene::remove(const std::string& path) {
    size_t erased = curves_.erase(path) + meshes_.erase(path) + cameras_.erase(path) + lights_.erase(path) +
                    materials_.erase(path);
    if (erased) version_ = nextVersion();
    return erased > 0;
}

void Scene::clear() {
    curves_.clear();
    meshes_.clear();
    cameras_.clear();
    lights_.clear();
    materials_.clear();
    version_ = nextVersion();
}

void Scene::updateFrom(const Scene& next) {
    auto update = [&](const auto& from, auto& to) {
        for (auto it = to.begin(); it != to.end();) {
            if (from.count(it->first)) {
                ++it;
            } else {
                it = to.erase(it);
                version_ = nextVersion();
            }
        }
        for (const auto& [path, entry] : from) set(to, *entry.prim);
    };
    update(next.curves_, curves_);
    update(next.meshes_, meshes_);
    update(next.cameras_, cameras_);
    update(next.lights_, lights_);
    update(next.materials_, materials_);
    info_ = next.info_;
}

Scene Scene::subset(const std::function<bool(const std::string& path)>& keep) const {
    Scene result;
    auto copy = [&](const auto& from, auto& to) {
        for (const auto& [path, entry] : from)
            if (keep(path)) to.emplace(path, entry);
    };
    copy(curves_, result.curves_);
    copy(meshes_, result.meshes_);
    copy(cameras_, result.cameras_);
    copy(lights_, result.lights_);
    copy(materials_, result.materials_);
    result.info_ = info_;
    result.version_ = version_;
    return result;
}

const CameraPrim* Scene::findCamera(const std::string& path) const {
    auto it = cameras_.find(path);
    return it == cameras_.end() ? nullptr : it->second.prim.get();
}

const SceneEntry<MaterialPrim>* Scene::findMaterial(const std::string& path) const {
    auto it = materials_.find(path);
    return it == materials_.end() ? nullptr : &it->second;
}

const CurvesPrim* Scene::findCurves(const std::string& path) const {
    auto it = curves_.find(path);
    return it == curves_.end() ? nullptr : it->second.prim.get();
}

}  // namespace hdhair
