#pragma once
// The engine's scene: prims keyed by path, added, changed and removed one at a
// time (the way Hydra drives a delegate). Prims are held as immutable shared
// snapshots, so a render can keep using the version it started with while the
// front end replaces a prim. Each change bumps the prim's version, which lets
// caches of prepared data (curves, GPU buffers) update only what changed;
// setting a prim equal to the one there is no change.
// Not internally synchronised: one writer at a time.

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>

#include "hdHair/scene/CameraPrim.h"
#include "hdHair/scene/CurvesPrim.h"
#include "hdHair/scene/LightPrim.h"
#include "hdHair/scene/MaterialPrim.h"
#include "hdHair/scene/MeshPrim.h"

namespace hdhair {

enum class UpAxis { Y, Z };

// Layer metadata that affects rendering.
struct StageInfo {
    std::string sourceFile;
    UpAxis upAxis = UpAxis::Y;
    double metersPerUnit = 0.01;
    double startTimeCode = 0.0, endTimeCode = 0.0;
    double timeCodesPerSecond = 24.0;
};

template <typename Prim>
struct SceneEntry {
    std::shared_ptr<const Prim> prim;
    // Unique across the process, not just this scene: a cache that outlives a
    // scene (the renderer's prepared curves) must never mistake a prim of a
    // new scene, or of the next frame, for one it has already seen.
    uint64_t version = 0;
};

class Scene {
public:
    template <typename Prim>
    using Entries = std::map<std::string, SceneEntry<Prim>>;

    void setCurves(CurvesPrim prim);
    void setMesh(MeshPrim prim);
    void setCamera(CameraPrim prim);
    void setLight(LightPrim prim);
    void setMaterial(MaterialPrim prim);
    // Makes this scene hold `next`'s prims: new and changed prims are set,
    // prims `next` lacks are removed, and prims equal to what is here keep
    // their versions, so the renderer's caches of them stay (a stage read at
    // each frame of hdhair-record --frames).
    void updateFrom(const Scene& next);
    // Removes the prim at path, whatever its kind. Returns false if there was none.
    bool remove(const std::string& path);
    void clear();
    // The prims whose path `keep` accepts, with their versions: a filtered
    // view (by Hydra render tag, say) that the renderer's caches still know.
    Scene subset(const std::function<bool(const std::string& path)>& keep) const;

    const Entries<CurvesPrim>& curves() const { return curves_; }
    const Entries<MeshPrim>& meshes() const { return meshes_; }
    const Entries<CameraPrim>& cameras() const { return cameras_; }
    const Entries<LightPrim>& lights() const { return lights_; }
    const Entries<MaterialPrim>& materials() const { return materials_; }

    const CameraPrim* findCamera(const std::string& path) const;
    const CurvesPrim* findCurves(const std::string& path) const;
    // The material at `path` with its version; nullptr for "" or a path with none.
    const SceneEntry<MaterialPrim>* findMaterial(const std::string& path) const;

    StageInfo& info() { return info_; }
    const StageInfo& info() const { return info_; }

    // Changes with every edit; equal versions mean an identical scene.
    uint64_t version() const { return version_; }

private:
    template <typename Prim>
    void set(Entries<Prim>& entries, Prim prim);

    Entries<CurvesPrim> curves_;
    Entries<MeshPrim> meshes_;
    Entries<CameraPrim> cameras_;
    Entries<LightPrim> lights_;
    Entries<MaterialPrim> materials_;
    StageInfo info_;
    uint64_t version_ = 0;
};

}  // namespace hdhair
