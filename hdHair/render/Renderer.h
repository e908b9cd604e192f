#pragma once
// The engine's front door: renders a Scene as seen by a CameraView into a
// linear, pre-multiplied RGBA image and a depth image. Used by hdhair-record
// and, on a ProgressiveRenderer's thread, the Hydra render pass.
//
// Flow per frame: prepare changed curves and meshes on the CPU (in parallel,
// cached by prim version) -> the frame graph (RenderPlan) -> its passes on
// the render thread (FrameScheduler, FramePasses), which upload only what
// changed and read the images back.

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "hdHair/curves/PreparedCurves.h"
#include "hdHair/curves/StrandColorSource.h"
#include "hdHair/gl/GlContext.h"
#include "hdHair/gl/PassTimer.h"
#include "hdHair/plan/HairMaterial.h"
#include "hdHair/image/DisplayShader.h"
#include "hdHair/image/Image.h"
#include "hdHair/meshes/PreparedMesh.h"
#include "hdHair/plan/CameraView.h"
#include "hdHair/render/FrameCancellation.h"
#include "hdHair/render/FramePasses.h"
#include "hdHair/render/FrameControl.h"
#include "hdHair/plan/FramingBounds.h"
#include "hdHair/render/RenderOutputs.h"
#include "hdHair/plan/RenderPlan.h"
#include "hdHair/render/RenderResult.h"
#include "hdHair/plan/RenderSettings.h"
#include "hdHair/render/RenderStats.h"
#include "hdHair/render/ShadowMapCache.h"
#include "hdHair/render/StrandUploads.h"

namespace hdhair {

class Diagnostics;
class Scene;

namespace gl {
class GlRenderThread;
}  // namespace gl
struct FrameResources;

class Renderer {
public:
    // Starts the GL thread and context. Throws gl::GlUnavailableError.
    explicit Renderer(gl::GlBackend backend);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Prepares every changed curves prim (repairs are reported to
    // diagnostics) and returns the bounds the framing camera fits
    // (FramingBounds.h: outlying points left out, with a warning) of what is
    // visible, meshes included (their authored points: meshes are refined
    // when rendered, at the refine level the settings give).
    SceneBounds prepare(const Scene& scene, const RenderSettings& settings, Diagnostics& diagnostics);

    // Throws FrameCancelled when control.cancellation stops the frame,
    // std::invalid_argument for a camera that is not finite, a preview that
    // would cast shadows, curves left out of a frame that is no preview, or
    // supersampling with the display transform on the GPU or beyond GL's
    // largest target; std::runtime_error when exact transparency does not fit
    // exactMemoryMB under exactOverflow=fail. With supersampling=N the frame
    // is rendered N x N times over and resolved (SupersampleResolve.h).
    RenderResult render(const Scene& scene, const CameraView& camera, const RenderSettings& settings,
                        Diagnostics& diagnostics, const RenderOutputs& outputs = {}, const FrameControl& control = {});

    const std::string& glDescription() const;
    // Where the GL context was made (GlContext::origin()): which EGL device
    // or platform, or OSMesa.
    const std::string& glDevice() const;

private:
    // A frame at the camera's own size: what render() does without
    // supersampling. It prepares what changed (prepareFrame), gathers what
    // the frame draws (gatherFrame), plans it (makeRenderPlan,
    // decideShadowMaps), runs the plan's passes on the GL thread (runFrame)
    // and reports what it did (reportFrame).
    RenderResult renderSamples(const Scene& scene, const CameraView& camera, const RenderSettings& settings,
                               Diagnostics& diagnostics, const RenderOutputs& outputs, const FrameControl& control);

    struct CachedCurves;
    // What a frame draws, gathered on the CPU before it is planned.
    struct GatheredFrame {
        FrameInputs inputs;
        std::vector<CachedCurves*> drawnCurves;  // the cache entries of inputs.drawn
        std::vector<HairMaterial> materials;     // the distinct materials inputs.drawn index
        StrandSummary strands;
        MeshSummary meshes;
        std::vector<DomeEnvironment> domes;      // the visible domes, fitted (frameDomeEnvironments)
        uint64_t curves = 0;
    };
    // The software-renderer warning once, and the curves and meshes that
    // changed since the last frame prepared.
    void prepareFrame(const Scene& scene, const RenderSettings& settings, Diagnostics& diagnostics,
                      RenderStats& stats);
    // The visible curves prims in draw order, their materials and the
    // strands' summary (gatherDrawnCurves); their uploads, the domes, the
    // materials' upload, the sort's spans and the meshes.
    GatheredFrame gatherFrame(const Scene& scene, const CameraView& camera, const RenderSettings& settings,
                              Diagnostics& diagnostics, const FrameControl& control, RenderStats& stats);
    void gatherDrawnCurves(const Scene& scene, const CameraView& camera, const RenderSettings& settings,
                           Diagnostics& diagnostics, GatheredFrame& frame, RenderStats& stats);
    // The plan's passes on the GL thread. Throws FrameCancelled, or
    // std::runtime_error when the frame failed (exactOverflow=fail).
    // Returns what a pass found that makes the plan impossible, if one did.
    std::optional<FrameFallback> runFrame(FrameInputs& inputs, RenderResult& result, Diagnostics& diagnostics,
                                          const FrameControl& control);
    // The frame's warnings and statistics.
    void reportFrame(const Scene& scene, const CameraView& camera, const RenderSettings& settings,
                     const GatheredFrame& frame, Diagnostics& diagnostics, RenderResult& result);

    // Prepares the curves prims that changed since they were last prepared
    // (or were prepared for another rendering space).
    void prepareChangedCurves(const Scene& scene, const RenderSettings& settings, Diagnostics& diagnostics);

    struct CachedCurves {
        uint64_t version = 0;
        // The bound material's version (0 when none): its colour and opacity
        // are baked into the prepared control points.
        uint64_t colorMaterialVersion = 0;
        // The space the prepared colours were converted into.
        RenderingSpace space = RenderingSpace::LinearRec709;
        std::shared_ptr<const PreparedCurves> prepared;
        float minSpanWidth = 0.0f;  // thinnest width at any span end
        float maxWidth = 0.0f;      // widest control point (shadow views' margins)
        // Every span's Bezier control polygon length, which bounds the span's
        // (shadowSampling=auto).
        std::vector<float> spanLengths;
        // The spans' mean control polygon length and mean width (at their
        // ends), for the fragments a span lists (strandRaster=auto).
        float meanSpanLength = 0.0f, meanSpanWidth = 0.0f;
        bool fullyOpaque = true;    // every control point's opacity is exactly 1
        // The prim's material, resolved once per version and material
        // settings (hairMaterialSettingsKey), and its per-point parameters.
        std::optional<HairMaterial> material;
        std::string materialSettings;
        std::vector<glm::vec4> parameterPoints;
        std::vector<uint16_t> sortHashes;  // per segment, for the bin sort (BinSort.h)
    };

    // The frame's hair materials for the GPU, when they or the prims'
    // ranges changed since they were last sent (else nothing).
    std::optional<MaterialUpload> materialUpload(const std::vector<HairMaterial>& materials,
                                                 const std::vector<CachedCurves*>& drawnCurves,
                                                 const std::vector<DrawnPrim>& drawn, const StrandUploadPlan& uploads,
                                                 bool srbfTables, Diagnostics& diagnostics);
    // Which shadow maps the frame rebuilds and which it keeps (ShadowMapCache),
    // for the maps an enabled pass of the provisional plan reads; the lights
    // an earlier attempt could not build a map for get none.
    ShadowMapAssignment decideShadowMaps(const RenderPlan& provisional, const StrandSummary& summary,
                                         const FrameFallbacks& fallbacks, Diagnostics& diagnostics, RenderStats& stats);
    // The plan a frame runs, made whole before it runs: a provisional plan
    // says which shadow maps are read, the shadow map cache decides them, and
    // the plan is made again with them (a preview draws no maps).
    RenderPlan planFrame(const Scene& scene, const CameraView& camera, const RenderSettings& settings,
                         const GatheredFrame& frame, const PlanRequest& request, const FrameControl& control,
                         Diagnostics& diagnostics, RenderStats& stats);

    // What the renderer keeps between frames, and who owns each: the
    // prepared curves and their materials, by prim path (curves_,
    // prepareChangedCurves); the prepared meshes (meshes_, prepareMeshes);
    // where each prim's strands sit on the GPU (uploads_, StrandUploads.h);
    // the materials last sent and their Marschner tables (uploadedMaterials_
    // and the three below it, marschnerTables_, srbfTables_: materialUpload);
    // the mesh buffer's contents (uploadedMeshes_, meshUpload); the shadow
    // maps (shadowMaps_, ShadowMapCache.h, with castersVersion_:
    // decideShadowMaps); the GPU objects themselves (resources_, on the GL
    // thread). Dome fits are cached by DomeTextureFitCache, outside the
    // renderer. Prepared curves and meshes leave with their prims; the
    // Marschner tables are kept, one per material ever drawn, for the
    // renderer's life.
    std::unique_ptr<gl::GlRenderThread> glThread_;
    std::unique_ptr<FrameResources> resources_;  // created and destroyed on the GL thread
    gl::PassTiming passTiming_ = gl::PassTiming::CpuSynchronised;  // when passTimings is on
    StrandUploads uploads_;
    std::vector<HairMaterial> uploadedMaterials_;
    std::vector<gl::SegmentRange> materialRanges_;  // the prims' ranges when the materials were sent
    std::vector<uint64_t> materialFirstControls_;   // and where their control points started
    bool materialSrbfTables_ = false;               // and whether they carried dome lighting's tables
    SrbfMaterialTables srbfTables_;
    struct CachedTables {
        HairMaterial material;
        std::vector<uint16_t> halfTexels;
        int width = 0, height = 0;
    };
    // A deque: material uploads keep pointers to the texels of earlier entries
    // while later ones are added (a vector would move them).
    std::deque<CachedTables> marschnerTables_;
    // Dual-scattering materials' fibre layers (DualScatteringTable::halfLayer),
    // likewise, the size of a Marschner table's layer.
    std::deque<CachedTables> dualScatteringTables_;
    std::map<std::string, CachedCurves> curves_;

    struct CachedMesh {
        uint64_t version = 0;
        int refineLevel = 0;  // the level asked for: the prim's, or the meshRefineLevel setting
        RenderingSpace space = RenderingSpace::LinearRec709;  // of the prepared colours
        std::shared_ptr<const PreparedMesh> prepared;
    };
    // Refines and triangulates every changed mesh (in parallel), cached per
    // prim version and refine level.
    void prepareMeshes(const Scene& scene, const RenderSettings& settings, Diagnostics& diagnostics);
    // The meshes a frame draws and whether the GPU's copy is stale.
    MeshUpload meshUpload(const Scene& scene, MeshSummary& summary);
    std::map<std::string, CachedMesh> meshes_;
    // What the mesh buffer holds: each mesh drawn last, with its ids.
    std::vector<std::pair<std::shared_ptr<const PreparedMesh>, glm::ivec2>> uploadedMeshes_;
    ShadowMapCache shadowMaps_;
    // Changes whenever the strands on the GPU do: the casters of every shadow.
    uint64_t castersVersion_ = 0;
    std::vector<gl::SegmentRange> castersRanges_;  // the draw ranges castersVersion_ describes
    // Preparation since the last render (framing may prepare first).
    double pendingPrepareMilliseconds_ = 0.0;
    size_t pendingPreparedPrims_ = 0;
    size_t pendingPreparedMeshes_ = 0;
    // The context's software-renderer warning goes to the first frame's
    // diagnostics only: it is about the machine, not about any one frame.
    bool glWarningReported_ = false;
};

}  // namespace hdhair
