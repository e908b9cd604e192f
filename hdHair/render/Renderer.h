#pragma once
// The engine's front door: renders a Scene as seen by a CameraView into a
// linear, pre-multiplied RGBA image and a depth image. Used by hdhair-record
// and (later) the Hydra render pass.
//
// Flow per frame: prepare changed curves on the CPU (in parallel, cached by
// prim version) -> plan -> GL passes on the render thread -> read back.

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "hdHair/curves/PreparedCurves.h"
#include "hdHair/curves/StrandColorSource.h"
#include "hdHair/gl/GlContext.h"
#include "hdHair/render/HairMaterial.h"
#include "hdHair/image/Image.h"
#include "hdHair/render/CameraView.h"
#include "hdHair/render/RenderPlan.h"
#include "hdHair/render/RenderSettings.h"
#include "hdHair/render/RenderStats.h"

namespace hdhair {

class Diagnostics;
class Scene;

namespace gl {
class FragmentListPass;
class GlRenderThread;
class HairMaterialTable;
class LightBatchAccumulation;
class RenderTarget;
class StrandGeometry;
class StrandPass;
}  // namespace gl

struct SceneBounds {
    glm::dvec3 min{1.0}, max{-1.0};  // min > max when the scene has nothing visible
    bool empty() const { return min.x > max.x; }
};

// What a frame must produce besides colour and depth.
struct RenderOutputs {
    // primId, instanceId and elementId images (for Hydra's picking and
    // selection). Off by default: id attachments are made only when asked for.
    bool ids = false;
};

struct RenderResult {
    Image color;  // RGBA, scene-linear, pre-multiplied
    // One channel, window depth in [0, 1], 1 where empty. Blended frames: the
    // depth of the nearest fragment of alpha >= kNearestStrandMinAlpha
    // (NearestStrandRule.h), whether or not ids are asked for.
    Image depth;
    // With RenderOutputs::ids: per pixel, rows from the top down; -1 where
    // empty. The same fragment as depth, on every path.
    std::vector<int32_t> primIds, instanceIds, elementIds;
    RenderPlan plan;
    RenderStats stats;
};

class Renderer {
public:
    // Starts the GL thread and context. Throws gl::GlUnavailableError.
    explicit Renderer(gl::GlBackend backend);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Prepares every changed curves prim (repairs are reported to
    // diagnostics) and returns the world bounds of what is visible.
    SceneBounds prepare(const Scene& scene, Diagnostics& diagnostics);

    RenderResult render(const Scene& scene, const CameraView& camera, const RenderSettings& settings,
                        Diagnostics& diagnostics, const RenderOutputs& outputs = {});

    const std::string& glDescription() const;

private:
    struct CachedCurves {
        uint64_t version = 0;
        // The bound material's version (0 when none): its colour and opacity
        // are baked into the prepared control points.
        uint64_t colorMaterialVersion = 0;
        std::shared_ptr<const PreparedCurves> prepared;
        float minSpanWidth = 0.0f;  // thinnest width at any span end
        bool fullyOpaque = true;    // every control point's opacity is exactly 1
        // The prim's material, resolved once per version and material
        // settings (hairMaterialSettingsKey), and its per-point parameters.
        std::optional<HairMaterial> material;
        std::string materialSettings;
        std::vector<glm::vec4> parameterPoints;
    };

    struct VisiblePrim {
        int primId;
        int instanceId;
        CachedCurves* cached;
        int material;  // index into the frame's materials
    };
    // Combines the visible prims into one geometry (when the set, a version
    // or a material assignment changed).
    void updateGeometry(const std::vector<VisiblePrim>& visible, const std::vector<uint64_t>& key, RenderStats& stats);
    // Uploads the frame's materials, the per-point parameters of prims whose
    // parameters vary, and the Marschner tables (built once per distinct
    // parameter set and kept). After updateGeometry: per-point records are
    // indexed by segment.
    void updateMaterials(const std::vector<HairMaterial>& materials, const std::vector<VisiblePrim>& visible);

    std::unique_ptr<gl::GlRenderThread> glThread_;
    std::unique_ptr<gl::StrandPass> strandPass_;
    std::unique_ptr<gl::FragmentListPass> fragmentListPass_;
    std::unique_ptr<gl::LightBatchAccumulation> lightBatchAccumulation_;
    std::unique_ptr<gl::HairMaterialTable> materialTable_;
    std::vector<HairMaterial> uploadedMaterials_;
    std::vector<uint64_t> materialsGeometryKey_;  // geometryKey_ when the materials were uploaded
    struct CachedTables {
        HairMaterial material;
        std::vector<uint16_t> halfTexels;
        int width = 0, height = 0;
    };
    std::vector<CachedTables> marschnerTables_;
    std::unique_ptr<gl::RenderTarget> target_;
    std::unique_ptr<gl::RenderTarget> batchTarget_;  // light batches after the first render here
    std::unique_ptr<gl::StrandGeometry> geometry_;  // created and destroyed on the GL thread
    std::vector<uint64_t> geometryKey_;             // prim versions and material indices geometry_ holds
    std::vector<StrandControlPoint> controlPoints_; // CPU copy, for sorting
    int maxSamples_ = 0;
    std::map<std::string, CachedCurves> curves_;
    std::set<std::string> reportedMeshes_;  // meshes already warned about as not drawn
    // Preparation time since the last render (framing may prepare first).
    double pendingPrepareMilliseconds_ = 0.0;
};

}  // namespace hdhair
