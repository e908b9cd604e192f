#pragma once
// What every prim's Sync and the render pass share: the engine's scene
// (written by prims syncing in parallel, hence the mutex), the renderer with
// its GL thread (created on first use, on the host thread that renders), and
// the warnings raised while preparing curves.

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
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
    void SetCurves(HdRprim const* rprim, hdhair::CurvesPrim prim, int refineLevel);
    void SetMesh(HdRprim const* rprim, hdhair::MeshPrim prim);
    void SetLight(hdhair::LightPrim light);
    void Remove(std::string const& path);

    // The prims a render pass draws: rprims whose render tag is among
    // `renderTags` (all when empty), every light; versions intact. Also the
    // highest refine level among the curves drawn.
    hdhair::Scene Snapshot(TfTokenVector const& renderTags, int* maxRefineLevel) const;
    uint64_t GetSceneVersion() const;

    // Creates the renderer (and its GL context) on first use. Throws
    // hdhair::gl::GlUnavailableError.
    hdhair::Renderer& GetRenderer();
    hdhair::Diagnostics& GetDiagnostics() { return _diagnostics; }

    // How many times each prim was synced: tests check that an edit re-syncs
    // only the prim it touched.
    size_t GetSyncCount(std::string const& path) const;
    std::map<std::string, size_t> GetSyncCounts() const;

private:
    struct Rprim {
        HdRprim const* rprim = nullptr;
        int refineLevel = 0;
    };

    mutable std::mutex _mutex;
    hdhair::Scene _scene;
    std::map<std::string, Rprim> _rprims;
    std::map<std::string, size_t> _syncCounts;
    std::mutex _rendererMutex;
    std::unique_ptr<hdhair::Renderer> _renderer;
    hdhair::Diagnostics _diagnostics;
};

PXR_NAMESPACE_CLOSE_SCOPE
