#pragma once
// What every prim's Sync and the render pass share: the engine's scene
// (written by prims syncing in parallel, hence the mutex; render passes take
// snapshots of it), the renderer with its GL thread (created on first use,
// on the host thread that renders; passes render with it on their
// ProgressiveRenderer's thread, one frame at a time), and the warnings
// raised while preparing curves and rendering.

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>
#include <string>

#include "pxr/imaging/hd/renderDelegate.h"
#include "pxr/imaging/hd/rprim.h"

#include "hdHair/base/Diagnostics.h"
#include "hdHair/render/Renderer.h"
#include "hdHair/scene/Scene.h"

PXR_NAMESPACE_OPEN_SCOPE

class HdHairRenderParam final : public HdRenderParam {
public:
    HdHairRenderParam();
    ~HdHairRenderParam() override;

    // Thread-safe: called from rprim and sprim Sync.
    // An instanced prim (`instanceTransforms` set) becomes one engine prim
    // per instance, named "<path>{i}", with that instance's world transform
    // and instanceId i; each is prepared on its own (memory and preparation
    // grow with the instance count; GPU instancing would share them).
    void SetCurves(HdRprim const* rprim, hdhair::CurvesPrim prim, int refineLevel,
                   std::optional<std::vector<glm::dmat4>> const& instanceTransforms);
    // The same for a mesh; its refine level is the prim's own (MeshPrim::refineLevel).
    void SetMesh(HdRprim const* rprim, hdhair::MeshPrim prim,
                 std::optional<std::vector<glm::dmat4>> const& instanceTransforms);
    void SetLight(hdhair::LightPrim light);
    void SetMaterial(hdhair::MaterialPrim material);
    void Remove(std::string const& path);

    static std::string InstancePath(std::string const& path, size_t instance);

    // The prims a render pass draws: rprims whose render tag is among
    // `renderTags` (all when empty), every light; versions intact. Also the
    // highest refine level among the curves and meshes drawn.
    hdhair::Scene Snapshot(TfTokenVector const& renderTags, int* maxRefineLevel) const;
    uint64_t GetSceneVersion() const;

    // Creates the renderer (and its GL context) on first use. Throws
    // hdhair::gl::GlUnavailableError.
    hdhair::Renderer& GetRenderer();
    // Held around each frame the renderer renders (hdhair::ProgressiveRenderer).
    std::mutex& GetRendererMutex() { return _frameMutex; }
    hdhair::Diagnostics& GetDiagnostics() { return _diagnostics; }

    // What the last full frame did (RenderStats as JSON, and the plan as
    // --explain prints it), for the delegate's render stats: hosts such as
    // hdhair-record --reader usd report them.
    void SetLastFrame(std::string statsJson, std::string plan);
    std::pair<std::string, std::string> GetLastFrame() const;

    // What the render pass last put into its buffers ("preview", "final",
    // "failed"; "none" before any), whether its renderer is working on a
    // view, how many previews and full frames it finished, how many full
    // frames a newer view stopped, and how far the last preview was cut
    // down: for the render stats, where hosts and tests see progress.
    // Updated whenever the pass executes.
    struct Progress {
        std::string shown = "none";
        // Why, when `shown` is "failed": the one-line reason the host was
        // also given as a TF_RUNTIME_ERROR (a camera that cannot be used, no GL).
        std::string error;
        bool rendering = false;
        uint64_t previews = 0, finals = 0, cancelled = 0;
        // How far the last preview shown was cut down (InteractivePreview.h).
        int previewPixelDivisor = 0, previewCurveStride = 0;
    };
    void SetProgress(Progress progress);
    Progress GetProgress() const;

    // How many times each prim was synced: tests check that an edit re-syncs
    // only the prim it touched.
    size_t GetSyncCount(std::string const& path) const;
    std::map<std::string, size_t> GetSyncCounts() const;

private:
    // Drops the engine prims of an rprim (itself, or its instances). Locked by the caller.
    void _RemoveEnginePrims(std::string const& path);
    // SetCurves and SetMesh: the prim, or one copy per instance, set with `set`.
    template <typename Prim>
    void _SetInstanced(HdRprim const* rprim, Prim prim, int refineLevel,
                       std::optional<std::vector<glm::dmat4>> const& instanceTransforms,
                       void (hdhair::Scene::*set)(Prim));

    struct Rprim {
        HdRprim const* rprim = nullptr;
        int refineLevel = 0;
    };

    mutable std::mutex _mutex;
    hdhair::Scene _scene;
    std::map<std::string, Rprim> _rprims;                   // by engine prim path
    std::map<std::string, std::vector<std::string>> _instancePaths;  // instanced rprim -> its engine prims
    std::map<std::string, size_t> _syncCounts;
    std::string _lastFrameStats, _lastFramePlan;
    Progress _progress;
    std::mutex _rendererMutex;  // creating the renderer
    std::mutex _frameMutex;     // rendering with it
    std::unique_ptr<hdhair::Renderer> _renderer;
    hdhair::Diagnostics _diagnostics;
};

PXR_NAMESPACE_CLOSE_SCOPE
