#pragma once
// Which lights cast shadows in a frame and how: the shadow settings, a
// light view fitted to the casters for every light that casts one, where
// its map is looked up (per fragment or per tessellated point) and how the
// strands are drawn into it. Everything that shapes a map is a field of
// ShadowPlan and takes part in its operator==, which is the shadow map
// cache's key (ShadowMapCache.h): a setting that changes the maps is added
// here, in planShadows and in ShadowPlan::mapShape, and nowhere else.

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "hdHair/curves/HairDensityGrid.h"
#include "hdHair/plan/FrameGraph.h"
#include "hdHair/plan/SettingTokens.h"
#include "hdHair/plan/ShadowLightView.h"

namespace hdhair {

struct LightPlan;
struct MeshSummary;
struct SettingValues;
struct StrandSummary;

// shadowSampling: vertex shadows' points at most this many texels of the
// finest map apart, and the most segments a span that cut may average for
// auto to take vertex shadows (planShadowSampling).
constexpr double kVertexShadowTexels = 2.0;
constexpr double kVertexShadowSegmentsPerSpan = 4.0;

// The widest strand, in texels, a light view draws as a one-texel line
// (planStrandLines, ShadowPlanner.cpp).
constexpr double kMaxStrandLineTexels = 1.5;

// A light that casts shadows (ShadingLight::castsShadow) in this frame.
struct PlannedShadow {
    size_t light = 0;       // index into LightPlan::lights.lights
    std::string key;        // the light's path, or "camera light"
    ShadowLightView view;   // not valid: no map, the light shades unshadowed (view.fallback says why)
    // With meshes (ShadowPlan::meshesCast): the view the meshes' depth is
    // drawn from, fitted to the hair and the meshes together, so that meshes
    // shadow the hair, themselves and each other wherever they are; the
    // hair's own maps keep their tighter view. Where the two cannot be held
    // by one view (a light among the meshes) it is the hair's view, and
    // `meshFallback` says what that leaves out; without a valid view of
    // either, the meshes are unshadowed by this light (meshFallback says why).
    ShadowLightView meshView;
    std::string meshFallback;
    // Shadowed through the hair's density volume (ShadowPlan::volumeGrid)
    // rather than a map: shadowMode=volume, or auto for a light its view
    // cannot hold (inside the hair: view.needsCubeMap). `volumeReason` says
    // which, for --explain.
    bool byVolume = false;
    std::string volumeReason;
    // The renderer's decision for its map (ShadowMapAssignment, below),
    // copied in when the plan is made: never changed while the frame runs.
    bool assigned = false;  // decided: the plan the frame runs
    int slot = -1;          // where its map lives (gl::ShadowMapStorage); -1: no map
    bool rebuild = true;    // false: kept from an earlier frame (ShadowMapCache)
    std::string reason;     // "rebuilt: ...", "kept: ..." or why it has no map
    bool overBudget = false;  // no map because shadowMemoryMB holds no more (one warning for all)
    // Deep opacity maps: the strands are drawn into this light's view as
    // one-texel lines (shadowStrandLines other than off, no strand much
    // wider than a texel there), not ribbons; `widestTexels` says why, for
    // --explain.
    bool strandLines = false;
    double widestTexels = 0.0;
    // With strand lines: the spans the view's tessellation leaves one
    // segment are drawn as plain lines, without the tessellator
    // (gl/LightViewSpans.h), not through it (shadowStrandLines=tessellated).
    bool straightSpans = false;
    // With straight spans: the view's lines come from the compute
    // rasteriser (gl/LightViewRaster.h) rather than the draws, under
    // strandRaster auto or compute when its per-layer sums fit in half of
    // shadowMemoryMB; `rasterReason` says which and why, for --explain.
    bool computeLines = false;
    std::string rasterReason;
};

struct ShadowPlan {
    // How the maps are drawn: deepOpacity under shadowMode auto, deepOpacity
    // and volume (the lights the volume shadows have no hair map, and the
    // meshes' depth is drawn all the same), reference or off.
    ShadowMode mode = ShadowMode::Off;
    ShadowMode setting = ShadowMode::Off;  // shadowMode as set
    int layers = 3;                // shadowLayers
    std::vector<float> boundaries;  // d_k / d_K (DeepOpacityLayers.h)
    double layerDepth = 1.0;       // shadowLayerDepth: d_K over the casters' depth range
    bool bilinear = true;          // shadowFilter (a lookup option: it shapes no map)
    // Deep opacity lookups at the tessellated points (shadowSampling), and
    // the longest a segment may be for them (world units; 0: the error
    // rule's cut): planShadows decides both.
    ShadowSampling samplingSetting = ShadowSampling::Auto;
    bool perVertex = false;
    double vertexSegmentLength = 0.0;
    std::string sampling;  // which, and why, for --explain; empty without deep opacity maps
    int resolution = 512;          // shadowMapResolution
    double minPixelWidth = 1.0;    // the coverage rule in the light's pixels, whatever the camera's path
    double tessellationTolerance = 0.5;  // shadowTessellationTolerance: texels (screenError only)
    // How the light views tessellate, as the camera does: tessellation,
    // pixelsPerSegment (projectedLength) and maxSegmentsPerSpan.
    Tessellation tessellation = Tessellation::ScreenError;
    double pixelsPerSegment = 8.0;
    int maxSegmentsPerSpan = 8;
    ShadowStrandLines strandLinesSetting = ShadowStrandLines::Auto;
    StrandRasterSetting rasterSetting = StrandRasterSetting::Auto;  // strandRaster: who draws the light views' lines
    int memoryMB = 1024;           // shadowMemoryMB
    int capacity = 0;              // map slots the storage holds (ShadowMapAssignment)
    std::vector<PlannedShadow> lights;
    // Casting lights left without a map because shadowMemoryMB holds only
    // `maxMaps` (shadowMapBudget); they shade unshadowed.
    size_t maxMaps = 0;
    size_t overBudget = 0;
    // The resource planned shadow `shadow` gives the strand passes
    // ("deepOpacity L", or "shadowFragments L" under shadowMode=reference).
    FrameResource resourceOf(size_t shadow) const {
        return {mode == ShadowMode::Reference ? ResourceKind::ShadowFragments : ResourceKind::DeepOpacity, shadow};
    }
    // Meshes are drawn, so every map has their depth too ("meshDepth L",
    // from PlannedShadow::meshView): the opaque occluders strands and meshes
    // test against.
    bool meshesCast = false;
    FrameResource meshResourceOf(size_t shadow) const { return {ResourceKind::MeshDepth, shadow}; }
    // SRBF lights without a map of their own that read another light's
    // (LightPlan::sharedMaps): light index -> the index of the light whose map.
    std::map<size_t, size_t> sharedMaps;
    // The hair density volume's grid, when a light is shadowed through it
    // (PlannedShadow::byVolume); empty otherwise. `volumeCoarsened`: the
    // densityVolumeMemoryMB budget made its voxels coarser than the size
    // kMaxDensityVoxelsAlong gives (`volumeNote` says how, for the warning).
    DensityGridShape volumeGrid;
    // Dual scattering's local back scattering reads the volume too
    // (multipleScattering:localTerm=densityVolume, a material where dual
    // scattering runs with d_b > 0, shadows on): d_b scaled by the share of
    // the light passing each fibre that the hair behind it intercepts.
    // `backScatteringReason` says why, or why not, for --explain.
    bool volumeBackScattering = false;
    std::string backScatteringReason;
    // The uniform dome's light reaches each strand through the hair as the
    // volume lets it (shadowMode auto, volume or reference, a uniform dome
    // that casts shadows): its visibility, averaged over six cones. The
    // maps cannot: a light from every direction has no view.
    // `domeOcclusionReason` says why, or why not, for --explain.
    bool volumeDomeOcclusion = false;
    std::string domeOcclusionReason;
    int volumeMemoryMB = 16;
    bool volumeCoarsened = false;
    std::string volumeNote;
    bool usesVolume() const { return !volumeGrid.empty(); }
    // domeShadowFilter=mipmap and some SRBF light reads a map: the
    // "opacityMipmaps" pass averages the opacity layers into a mip chain,
    // the convolution optical depth map those lights read ("convolvedOpacity").
    bool convolvedOpacity = false;
    // Index into `lights` of the shadow light `light` is shadowed by (its
    // own, or the one it shares), or -1.
    int shadowOf(size_t light) const;
    // Whether `shadow` has a map the lookups read: shadows on, a view, and
    // a slot (the renderer's, ShadowMapCache).
    bool isMapped(const PlannedShadow& shadow) const {
        return mode != ShadowMode::Off && shadow.view.valid && shadow.slot >= 0;
    }
    // Whether `shadow` has a mesh depth the lookups read: meshes cast, a
    // mesh view, and a slot. A frame without hair has mesh maps only.
    bool isMeshMapped(const PlannedShadow& shadow) const {
        return meshesCast && shadow.meshView.valid && shadow.slot >= 0;
    }

    // What shapes every map besides its light's view and the casters (each
    // light's view is compared by the cache, light by light). The mip chain
    // is here because adding or dropping it reallocates the opacity layers.
    auto mapShape() const {
        return std::tie(mode, layers, boundaries, layerDepth, samplingSetting, resolution, minPixelWidth,
                        tessellationTolerance, tessellation, pixelsPerSegment, maxSegmentsPerSpan, strandLinesSetting,
                        rasterSetting, convolvedOpacity);
    }
    // Two plans are equal when they draw the same maps (mapShape).
    bool operator==(const ShadowPlan& other) const { return mapShape() == other.mapShape(); }
    bool operator!=(const ShadowPlan& other) const { return !(*this == other); }
};

// How many shadow maps fit: the largest power of two (the map storage grows
// in powers of two, ShadowMapCache) whose maps fit in `memoryMB` at this
// resolution and layer count (R32F hair and mesh depths, RGBA16F per four
// layers) and within GL 4.5's guaranteed 2048 array layers.
size_t shadowMapBudget(int resolution, int layers, int memoryMB);

// The renderer's decision for each planned shadow (ShadowPlan::lights) whose
// map an enabled pass of the provisional plan reads (ShadowMapCache): its
// slot, and whether its passes rebuild it or it is kept from an earlier
// frame (an input of the graph then; its passes do not run). A shadow with
// slot -1 and a reason has no map: it shades unshadowed.
struct ShadowMapAssignment {
    struct Map {
        int slot = -1;
        bool rebuild = true;
        std::string reason;
    };
    std::vector<std::optional<Map>> maps;  // per planned shadow; empty: not decided (nothing reads it)
    int capacity = 0;                      // slots the map storage must hold
};

// The shadows of the lights `lights` planned: the settings, and a planned
// shadow for every light that casts one (its view fitted to the casters, or
// why it cannot be). Which SRBF lights share a map is the lights' to say.
// With `assignment` (the renderer's decision for each map) the plan draws
// its maps; without it, it is provisional: it says which maps are read.
// Throws std::invalid_argument when domeLighting=sampled has more shadowed
// lights than shadowMemoryMB holds maps: the reference must not shade a
// light unshadowed.
ShadowPlan planShadows(const LightPlan& lights, const SettingValues& settings, const StrandSummary& strands,
                       const MeshSummary& meshes, const std::optional<ShadowMapAssignment>& assignment);

}  // namespace hdhair
