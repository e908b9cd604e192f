#pragma once
// Which passes a frame runs, decided per scene before any GL work: only the
// effects a scene calls for are simulated, and what is off costs nothing.
// The plan is a FrameGraph (FrameGraph.h): each pass with what it reads and
// writes and the reason it runs or not, printed by --explain and kept, with
// each pass's time, in --stats.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "hdHair/render/DomeLighting.h"
#include "hdHair/render/FrameGraph.h"
#include "hdHair/render/ShadowLightView.h"
#include "hdHair/shading/ShadingLight.h"

namespace hdhair {

class RenderSettings;
class Scene;
struct CameraView;

// How the frame's strands are composited.
enum class TransparencyPath { Opaque, BinSorted, Exact, Unsorted };
const char* toString(TransparencyPath path);

// What the frame's strands need, measured on the prepared curves.
struct StrandSummary {
    uint64_t segments = 0;
    // Every control point fully opaque (1 exactly: then every interpolated
    // opacity is 1 too, Catmull-Rom weights summing to one).
    bool allOpaque = true;
    // The thinnest any strand can project, in pixels, at the far side of the
    // strands' bounds (conservative); infinity when there are none.
    double minProjectedWidthPixels = 0.0;
    bool anyLit = true;          // some prim's material is lit (not flat)
    std::string shadingModels;   // the models in use, e.g. "kajiyaKay+marschner"
    size_t perPointPrims = 0;    // prims whose hair parameters vary per curve or vertex
    size_t analyticPrims = 0;    // Marschner prims shaded with per-fragment azimuthal terms
    CasterBounds casters;        // what casts shadows: every drawn strand
    // Each drawn prim's span lengths (Bezier control polygons).
    std::vector<const std::vector<float>*> spanLengths;
    // The segments a span would get on average if each were cut into pieces
    // no longer than `length` by its control polygon (at least 1 each).
    double meanSegmentsOfAtMost(double length) const;
};

// How lights shadow the hair (the shadowMode setting).
enum class ShadowMode { DeepOpacity, Reference, Off };
const char* toString(ShadowMode mode);

// shadowSampling: vertex shadows' points at most this many texels of the
// finest map apart, and the most segments a span that cut may average for
// auto to take vertex shadows (planShadowSampling).
constexpr double kVertexShadowTexels = 2.0;
constexpr double kVertexShadowSegmentsPerSpan = 4.0;

// A light that casts shadows (ShadingLight::castsShadow) in this frame.
struct PlannedShadow {
    size_t light = 0;       // index into RenderPlan::lights.lights
    std::string key;        // the light's path, or "camera light"
    ShadowLightView view;   // not valid: no map, the light shades unshadowed (view.fallback says why)
    int slot = -1;          // where its map lives (gl::ShadowMapStorage), set by the renderer
    bool rebuild = true;    // false: kept from an earlier frame (ShadowMapCache)
    std::string reason;     // "rebuilt: ..." or "kept: ..." once the renderer decided
    bool overBudget = false;  // no map because shadowMemoryMB holds no more (one warning for all)
    // Deep opacity maps: the strands are drawn into this light's view as
    // one-texel lines (shadowStrandLines=auto, no strand much wider than a
    // texel there), not ribbons; `widestTexels` says why, for --explain.
    bool strandLines = false;
    double widestTexels = 0.0;
    // With strand lines: the spans the view's tessellation leaves one
    // segment are drawn as plain lines, without the tessellator
    // (shadowStrandLines=auto; gl/LightViewSpans.h), not through it
    // (shadowStrandLines=tessellated).
    bool straightSpans = false;
};

struct ShadowPlan {
    ShadowMode mode = ShadowMode::Off;
    int layers = 3;                // shadowLayers
    std::vector<float> boundaries;  // d_k / d_K (DeepOpacityLayers.h)
    double layerDepth = 1.0;       // shadowLayerDepth: d_K over the casters' depth range
    bool bilinear = true;          // shadowFilter
    // Deep opacity lookups at the tessellated points (shadowSampling), and
    // the longest a segment may be for them (world units; 0: the error
    // rule's cut): planShadows decides both.
    bool perVertex = false;
    double vertexSegmentLength = 0.0;
    std::string sampling;  // which, and why, for --explain; empty without deep opacity maps
    int resolution = 512;          // shadowMapResolution
    double minPixelWidth = 1.0;    // the coverage rule in the light's pixels, whatever the camera's path
    double tessellationTolerance = 0.5;  // shadowTessellationTolerance: texels (screenError only)
    int capacity = 0;              // map slots the storage holds (set by the renderer)
    std::vector<PlannedShadow> lights;
    // Casting lights left without a map because shadowMemoryMB holds only
    // `maxMaps` (shadowMapBudget); they shade unshadowed.
    size_t maxMaps = 0;
    size_t overBudget = 0;
    // The resource light `shadow` gives the strand passes ("deepOpacity L",
    // "shadowFragments L").
    std::string resourceOf(const PlannedShadow& shadow) const;
    // Meshes are drawn, so every map has their depth too ("meshDepth L",
    // the opaque occluders strands test against).
    bool meshesCast = false;
    std::string meshResourceOf(const PlannedShadow& shadow) const { return "meshDepth " + shadow.key; }
    // SRBF lights without a map of their own that read another light's
    // (DomeLighting.h): light index -> the index of the light whose map.
    std::map<size_t, size_t> sharedMaps;
    // domeShadowFilter=mipmap and some SRBF light reads a map: the
    // "opacityMipmaps" pass averages the opacity layers into a mip chain,
    // the convolution optical depth map those lights read ("convolvedOpacity").
    bool convolvedOpacity = false;
    // Index into `lights` of the shadow light `light` is shadowed by (its
    // own, or the one it shares), or -1.
    int shadowOf(size_t light) const;
};

// The most stage lights a frame shades; more are left out, in path order
// from the last, with a warning. Each light costs every strand drawn once
// more per lightsPerPass lights (hdHair/render/README.md, "Light cap").
constexpr size_t kMaxLights = 1024;

// How many shadow maps fit: the largest power of two (the map storage grows
// in powers of two, ShadowMapCache) whose maps fit in `memoryMB` at this
// resolution and layer count (R32F hair and mesh depths, RGBA16F per four
// layers) and within GL 4.5's guaranteed 2048 array layers.
size_t shadowMapBudget(int resolution, int layers, int memoryMB);

// What the frame's meshes need, measured on the prepared meshes.
struct MeshSummary {
    size_t meshes = 0;        // visible meshes with at least one triangle
    uint64_t triangles = 0;   // after refinement
    int minRefineLevel = 0, maxRefineLevel = 0;  // the levels drawn
    bool changed = false;     // the GPU copy must be sent again
};

// The passes, in the order they run:
//   upload        preparedStrands -> strands        GPU copy of the changed prims
//   meshUpload    preparedMeshes -> meshGeometry    GPU copy of the meshes, when one changed
//   sort          preparedStrands -> drawOrder      binSorted only
//   shadowDepth L      strands -> hairDepth L       per shadow-casting light L: its nearest hair
//   deepOpacity L      strands, hairDepth L -> deepOpacity L   its opacity layers
//   shadowFragments L  strands -> shadowFragments L  shadowMode=reference instead: every fragment
//   meshShadow L       meshGeometry -> meshDepth L  with meshes: the nearest mesh, which hides the hair behind it
//                 (a map kept from an earlier frame is an input of the graph instead)
//   clear         -> color, depth[, ids]            the frame's targets, empty
//   meshes        meshGeometry, color, depth[, ids] -> color, depth[, ids]   opaque, lights of batch 1
//   strands       strands[, drawOrder], color, depth[, the batch's shadows] -> color, depth[, ids]   lights of batch 1
//   ids           strands, depth -> ids             blended paths, when a host asks for ids
//   resolve       color, depth[, ids] (in place)    multisampled frames
//   lightBatch k  [strands[, drawOrder],] [meshGeometry,] color[, the batch's shadows] -> color   lights of batch k (k >= 2)
//   readback      color, depth[, ids] -> aovs       the frame's images, to the CPU
//   displayTransform  color -> displayImage         the display image on the GPU, when asked for
// Meshes are drawn first and write depth, so every strand path tests
// against them (NearestStrandRule.h: how their depth and ids combine with
// the strands').
struct RenderPlan {
    FrameGraph graph;
    ShadingLights lights;       // the stage's lights, plus the camera light when used
    bool cameraLight = false;
    TransparencyPath transparency = TransparencyPath::Opaque;
    uint32_t sortBins = 0;      // for BinSorted
    int msaaSamples = 0;        // for Opaque
    bool flatShading = false;   // every prim flat: no lights needed
    bool meshesLit = false;     // meshes shaded with the lights (Lambert), else displayColor unlit
    // Light passes: [begin, end) ranges of `lights.lights`, at most
    // lightsPerPass each; always at least one (ambient and unlit shading
    // need a pass too).
    std::vector<std::pair<size_t, size_t>> lightBatches;
    ShadowPlan shadows;
    // The domes as domeLighting=srbf shades them (empty with ambient).
    std::vector<PlannedDome> domes;
    // Stage lights beyond kMaxLights, left out of the frame.
    size_t lightsOverCap = 0;

    bool isEnabled(const std::string& name) const { return graph.isEnabled(name); }
    // Exact transparency over its memory budget: the frame is redrawn
    // binSorted with `bins` bins, which needs the ids pass when ids are asked for.
    void fallBackToBinSorted(uint32_t bins, bool idsRequested);
    // The renderer's decision for shadow `shadow` (ShadowMapCache): rebuilt
    // by its passes, or kept, when its map becomes an input of the graph and
    // its passes do not run.
    void setShadowMap(size_t shadow, int slot, bool rebuild, const std::string& reason);
    // Whether an enabled pass reads shadow `shadow`'s map.
    bool shadowUsed(size_t shadow) const;
    std::string describe() const { return graph.describe(); }  // for --explain
    nlohmann::json toJson() const;
};

// Whether a frame adds hdHair's camera light (a distant light from the
// eye): the cameraLight setting says on, or auto and the stage has no light
// of its own; never when nothing is lit (flat shading only).
bool usesCameraLight(const std::string& cameraLightSetting, bool stageHasLight, bool anythingLit);

// idsRequested: a host asked for primId/instanceId/elementId. Depth is always
// produced; with blending, by the strand pass (NearestStrandRule.h).
// displayOnGpu: the frame also delivers its display image, made on the GPU.
// domes: the visible domes as the renderer fitted them (frameDomeEnvironments);
// a dome it does not list counts as untextured.
RenderPlan makeRenderPlan(const Scene& scene, const RenderSettings& settings, const CameraView& camera,
                          const StrandSummary& strands, bool idsRequested = false, const MeshSummary& meshes = {},
                          bool displayOnGpu = false, const std::vector<DomeEnvironment>& domes = {});

}  // namespace hdhair
