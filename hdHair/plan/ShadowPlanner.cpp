#include "hdHair/plan/ShadowPlanner.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "hdHair/gl/LightViewRaster.h"
#include "hdHair/plan/DeepOpacityLayers.h"
#include "hdHair/plan/LightPlanner.h"
#include "hdHair/plan/SceneSummary.h"
#include "hdHair/plan/SettingValues.h"

namespace hdhair {

int ShadowPlan::shadowOf(size_t light) const {
    if (auto shared = sharedMaps.find(light); shared != sharedMaps.end()) light = shared->second;
    for (size_t i = 0; i < lights.size(); ++i)
        if (lights[i].light == light) return int(i);
    return -1;
}

namespace {

// Where the deep opacity maps are looked up (shadowSampling). Vertex shadows
// interpolate each light's transmittance along a segment, and a map
// resolves it to a texel: what matters is how far apart the points are in
// the finest map's texels (a texel at the casters' nearest depth for a
// perspective light), so spans longer than kVertexShadowTexels of it are cut
// to that length (FrameUniforms::shadowSegmentLength), beyond the error
// rule's cut. vertex always does this, which on stages of long spans costs
// many segments; auto only when that cut alone would average at most
// kVertexShadowSegmentsPerSpan segments a span (real grooms: the TressFX
// bear's and Ratboy's spans, which the error rule cuts about as finely
// anyway), else looks up per fragment; fragment, and reference shadows,
// always per fragment.
void planShadowSampling(ShadowPlan& shadows, ShadowSampling sampling, const StrandSummary& strands) {
    double finestTexel = 0.0;
    for (const PlannedShadow& shadow : shadows.lights) {
        if (!shadow.view.valid) continue;
        const double texel =
            shadow.view.texelSize * (shadow.view.orthographic ? 1.0 : std::max(shadow.view.nearDepth, 1e-6));
        if (texel > 0.0 && (finestTexel == 0.0 || texel < finestTexel)) finestTexel = texel;
    }
    const double longest = kVertexShadowTexels * finestTexel;
    shadows.perVertex = false;
    shadows.vertexSegmentLength = 0.0;
    shadows.sampling.clear();
    if (shadows.mode != ShadowMode::DeepOpacity || longest <= 0.0) return;
    const double segments = strands.meanSegmentsOfAtMost(longest);
    const std::string counted = fmt::format("spans cut to {} texels of the finest map ({:.3g}) would average {:.2f} "
                                            "segments",
                                            kVertexShadowTexels, longest, segments);
    if (sampling == ShadowSampling::Fragment) {
        shadows.sampling = "shadows looked up per fragment (shadowSampling=fragment)";
    } else if (sampling == ShadowSampling::Vertex || segments <= kVertexShadowSegmentsPerSpan) {
        shadows.perVertex = true;
        shadows.vertexSegmentLength = longest;
        shadows.sampling = fmt::format("shadows looked up per tessellated point: {} (shadowSampling={})", counted,
                                       toString(sampling));
    } else {
        shadows.sampling = fmt::format("shadows looked up per fragment: {}, over {} (shadowSampling=auto)", counted,
                                       kVertexShadowSegmentsPerSpan);
    }
}

// Whether a deep opacity map draws the strands as one-texel lines: when none
// is much wider than a texel (the widest authored width, at the casters'
// nearest depth for a perspective view). A ribbon under a texel wide is
// drawn a texel wide with its alpha scaled down (minPixelWidth, at most 1
// for lines to stand in for it); a line carries the same coverage, as alpha
// width / m (strandLinePoint.glsl), without the geometry shader that widens
// each segment. Up to kMaxStrandLineTexels (TressFX's roots are about a texel at
// 512) that alpha may pass 1: the texels a line lights sum the ribbon's
// opacity, in one texel where the ribbon spread it over two, a difference
// within the texel the bilinear lookup blurs over anyway. With `drawn` the
// spans the view leaves one segment skip the tessellator too; `tessellated`
// keeps every span on it, the path that check compares against; `compute`
// rasterises every span in compute (gl/LightViewRaster.h), on every core of
// llvmpipe; `auto` is compute unless strandRaster=hardware, then drawn.
void planStrandLines(PlannedShadow& shadow, const ShadowPlan& shadows, ShadowStrandLines setting, double maxWidth) {
    const ShadowLightView& view = shadow.view;
    if (!view.valid || shadows.mode != ShadowMode::DeepOpacity) return;
    const double texel = view.orthographic ? view.texelSize : view.texelSize * view.nearDepth;
    shadow.widestTexels = texel > 0.0 ? maxWidth / texel : std::numeric_limits<double>::infinity();
    shadow.strandLines = setting != ShadowStrandLines::Off && shadows.minPixelWidth <= 1.0 &&
                         shadow.widestTexels <= kMaxStrandLineTexels;
    shadow.straightSpans = shadow.strandLines && setting != ShadowStrandLines::Tessellated;
    if (!shadow.straightSpans) return;
    // The compute rasteriser: asked for (compute), or with the camera's
    // (auto, unless strandRaster=hardware); its layer sums must fit.
    const bool asked = setting == ShadowStrandLines::Compute ||
                       (setting == ShadowStrandLines::Auto && shadows.rasterSetting != StrandRasterSetting::Hardware);
    const double sumBytes = double(gl::LightViewRaster::layerSumBytes(shadows.resolution, shadows.layers));
    const bool fits = sumBytes <= 0.5 * double(shadows.memoryMB) * 1024.0 * 1024.0;
    shadow.computeLines = asked && fits;
    shadow.rasterReason =
        !asked ? (setting == ShadowStrandLines::Drawn ? "drawn (shadowStrandLines=drawn)" : "drawn (strandRaster=hardware)")
        : fits ? (setting == ShadowStrandLines::Compute
                      ? "rasterised in compute (shadowStrandLines=compute)"
                      : fmt::format("rasterised in compute (strandRaster={})", toString(shadows.rasterSetting)))
               : fmt::format("drawn: the compute rasteriser's layer sums ({:.0f} MB) need more than half of "
                             "shadowMemoryMB={}",
                             sumBytes / (1024.0 * 1024.0), shadows.memoryMB);
}

// The shadow settings, as a plan without lights.
ShadowPlan shadowSettings(const SettingValues& settings) {
    ShadowPlan shadows;
    shadows.setting = settings.shadowMode;
    shadows.mode = settings.shadowMode == ShadowMode::Auto || settings.shadowMode == ShadowMode::Volume
                       ? ShadowMode::DeepOpacity
                       : settings.shadowMode;
    shadows.volumeMemoryMB = settings.densityVolumeMemoryMB;
    shadows.layers = settings.shadowLayers;
    shadows.boundaries = deepOpacityLayerBoundaries(shadows.layers, settings.shadowLayerSpacing);
    shadows.layerDepth = settings.shadowLayerDepth;
    shadows.bilinear = settings.shadowFilter == ShadowFilter::Bilinear;
    shadows.samplingSetting = settings.shadowSampling;
    shadows.resolution = settings.shadowMapResolution;
    shadows.minPixelWidth = settings.minPixelWidth;
    shadows.tessellationTolerance = settings.shadowTessellationTolerance;
    shadows.tessellation = settings.tessellation;
    shadows.pixelsPerSegment = settings.pixelsPerSegment;
    shadows.maxSegmentsPerSpan = settings.maxSegmentsPerSpan;
    shadows.strandLinesSetting = settings.shadowStrandLines;
    shadows.rasterSetting = settings.strandRaster;
    shadows.memoryMB = settings.shadowMemoryMB;
    return shadows;
}

// The view the meshes' depth is drawn from: the hair and the meshes
// together, or, where one view cannot hold both, the hair's own (meshes then
// shadow what lies within the hair's view only, and `meshFallback` says so).
void fitMeshView(PlannedShadow& shadow, const ShadingLight& light, const ShadowPlan& shadows,
                 const StrandSummary& strands, const MeshSummary& meshes) {
    shadow.meshView = fitShadowLightView(light, unite(strands.casters, meshes.bounds), shadows.resolution);
    if (shadow.meshView.valid) return;
    const std::string why = shadow.meshView.needsCubeMap
                                ? "the light is inside or too close to the bounds of the hair and meshes for one "
                                  "perspective view (a cube map)"
                                : shadow.meshView.fallback;
    if (shadow.view.valid) {
        shadow.meshView = shadow.view;
        shadow.meshFallback = "meshes shadow each other only within the hair's light view: " + why;
    } else {
        shadow.meshFallback = "the meshes cast no shadows from this light: " + why;
    }
}

// Whether `shadow` is shadowed through the hair's density volume: every
// light under shadowMode=volume; under auto, a light whose view cannot hold
// the hair (a local light inside or too close to it, which one perspective
// view cannot see: a cube map would), with strands to shadow. deepOpacity
// keeps such a light unshadowed (warned), as before the volume existed.
void planVolumeShadow(PlannedShadow& shadow, ShadowMode setting, const StrandSummary& strands) {
    if (strands.casters.empty()) return;
    if (setting == ShadowMode::Volume) {
        shadow.byVolume = true;
        shadow.volumeReason = "through the hair's density volume (shadowMode=volume)";
        shadow.view.fallback = "shadowMode=volume: no map, the density volume instead";
    } else if (setting == ShadowMode::Auto && !shadow.view.valid && shadow.view.needsCubeMap) {
        shadow.byVolume = true;
        shadow.volumeReason = "through the hair's density volume (shadowMode=auto): the light is inside or too "
                              "close to the hair's bounds for one map's view";
    }
}

// Whether dual scattering's local term reads the density volume, and why
// (or why not, where a material has dual scattering).
void planVolumeBackScattering(ShadowPlan& shadows, const SettingValues& settings, const StrandSummary& strands) {
    if (strands.dualScatteringMaterials == 0 || strands.casters.empty()) return;
    if (settings.multipleScatteringLocalTerm == DualScatteringLocalTerm::Constant) {
        shadows.backScatteringReason = "local back scattering d_b everywhere (multipleScattering:localTerm=constant)";
    } else if (!(settings.multipleScatteringBackDensity > 0.0)) {
        shadows.backScatteringReason = "no local back scattering (multipleScattering:backDensity=0)";
    } else if (shadows.mode == ShadowMode::Off) {
        shadows.backScatteringReason = "local back scattering d_b everywhere: shadowMode=off builds no density volume";
    } else {
        shadows.volumeBackScattering = true;
        shadows.backScatteringReason = "local back scattering from the hair behind each fibre in the density volume "
                                       "(multipleScattering:localTerm=densityVolume)";
    }
}

// Whether the uniform dome reaches the strands through the density volume,
// and why (or why not, where there is a uniform dome over hair).
void planVolumeDomeOcclusion(ShadowPlan& shadows, const ShadingLights& lights, const StrandSummary& strands) {
    if (!(glm::length(lights.uniformDome) > 0.0f) || strands.casters.empty()) return;
    if (!lights.uniformDomeCastsShadow) {
        shadows.domeOcclusionReason = "the uniform dome unshadowed: it casts no shadows (inputs:shadow:enable)";
    } else if (shadows.mode == ShadowMode::Off) {
        shadows.domeOcclusionReason = "the uniform dome unshadowed (shadowMode=off)";
    } else if (shadows.setting == ShadowMode::DeepOpacity) {
        shadows.domeOcclusionReason = "the uniform dome unshadowed: maps need a direction (shadowMode=deepOpacity)";
    } else {
        shadows.volumeDomeOcclusion = true;
        shadows.domeOcclusionReason =
            fmt::format("the uniform dome through the density volume, six cones (shadowMode={})",
                        toString(shadows.setting));
    }
}

// The density volume's grid over the hair, when a light, the uniform dome
// or dual scattering reads it: as fine as kMaxDensityVoxelsAlong gives, or
// as densityVolumeMemoryMB holds with its mip chain (a seventh more).
void planVolumeGrid(ShadowPlan& shadows, const StrandSummary& strands) {
    const bool read = shadows.volumeBackScattering || shadows.volumeDomeOcclusion ||
                      std::any_of(shadows.lights.begin(), shadows.lights.end(),
                                  [](const PlannedShadow& shadow) { return shadow.byVolume; });
    if (!read) return;
    const CasterBounds& casters = strands.casters;
    const size_t maxVoxels = size_t(shadows.volumeMemoryMB) * 1024 * 1024 / sizeof(float) * 7 / 8;
    shadows.volumeGrid = fitDensityGrid(casters.min, casters.max, maxVoxels);
    const DensityGridShape finest = fitDensityGrid(casters.min, casters.max, std::numeric_limits<size_t>::max());
    shadows.volumeCoarsened = !shadows.volumeGrid.empty() && shadows.volumeGrid.voxelSize > finest.voxelSize;
    if (shadows.volumeCoarsened)
        shadows.volumeNote = fmt::format("densityVolumeMemoryMB={} holds {}x{}x{} voxels of {:.3g}, coarser than the "
                                         "{:.3g} the hair's size calls for",
                                         shadows.volumeMemoryMB, shadows.volumeGrid.dims.x, shadows.volumeGrid.dims.y,
                                         shadows.volumeGrid.dims.z, shadows.volumeGrid.voxelSize, finest.voxelSize);
}

// Light views fitted to the casters for `shadow` (the hair's, and with
// meshes the meshes' too), while shadowMemoryMB holds another map (`mapped`
// so far); past that, why it has none. Whether the density volume shadows
// it instead, which needs no map.
void fitView(PlannedShadow& shadow, const ShadingLight& light, ShadowPlan& shadows, const StrandSummary& strands,
             const MeshSummary& meshes, size_t& mapped) {
    if (shadows.setting != ShadowMode::Volume && mapped < shadows.maxMaps)
        shadow.view = fitShadowLightView(light, strands.casters, shadows.resolution);
    planVolumeShadow(shadow, shadows.setting, strands);
    if (mapped < shadows.maxMaps) {
        if (shadows.meshesCast) fitMeshView(shadow, light, shadows, strands, meshes);
        mapped += shadow.view.valid || shadow.meshView.valid ? 1 : 0;
        return;
    }
    if (shadow.byVolume) return;  // the volume needs no slot; only the meshes' depth goes unshadowed
    shadow.view.valid = false;
    shadow.overBudget = true;
    shadow.view.fallback = fmt::format("shadowMemoryMB={} holds {} maps of {}x{} texels", shadows.memoryMB,
                                       shadows.maxMaps, shadows.resolution, shadows.resolution);
    shadows.overBudget += 1;
}

// domeLighting=sampled is the reference the SRBF path's shadows are
// measured against (DomeLighting.h): it must not shade lights unshadowed,
// so a frame that draws shadows with more casting lights than maps fits is
// a settings error, not a warning.
void checkSampledDomesShadowed(const ShadowPlan& shadows, const LightPlan& lights, const StrandSummary& strands) {
    if (shadows.overBudget == 0 || !lights.domesSampled || lights.flatShading || strands.segments == 0) return;
    throw std::invalid_argument(
        fmt::format("domeLighting=sampled: {} lights cast shadows, more than the {} maps shadowMemoryMB={} holds at "
                    "shadowMapResolution={} ({} would be drawn unshadowed); lower domeSampledLights or "
                    "shadowMapResolution, or raise shadowMemoryMB",
                    shadows.lights.size(), shadows.maxMaps, shadows.memoryMB, shadows.resolution, shadows.overBudget));
}

// Copies the renderer's decisions into the planned shadows.
void assignShadowMaps(ShadowPlan& shadows, const ShadowMapAssignment& assignment) {
    if (assignment.maps.size() != shadows.lights.size())
        throw std::logic_error("shadow map assignment: one decision per planned shadow expected");
    shadows.capacity = assignment.capacity;
    for (size_t i = 0; i < shadows.lights.size(); ++i) {
        if (!assignment.maps[i]) continue;
        PlannedShadow& shadow = shadows.lights[i];
        shadow.assigned = true;
        shadow.slot = assignment.maps[i]->slot;
        shadow.rebuild = assignment.maps[i]->rebuild;
        shadow.reason = assignment.maps[i]->reason;
    }
}

}  // namespace

ShadowPlan planShadows(const LightPlan& lights, const SettingValues& settings, const StrandSummary& strands,
                       const MeshSummary& meshes, const std::optional<ShadowMapAssignment>& assignment) {
    ShadowPlan shadows = shadowSettings(settings);
    shadows.sharedMaps = lights.sharedMaps;
    shadows.meshesCast = meshes.meshes > 0 && shadows.mode != ShadowMode::Off;
    shadows.maxMaps = shadowMapBudget(shadows.resolution, shadows.layers, shadows.memoryMB);
    size_t mapped = 0;
    for (size_t i = 0; i < lights.lights.lights.size(); ++i) {
        const ShadingLight& light = lights.lights.lights[i];
        if (!light.castsShadow) continue;
        PlannedShadow shadow;
        shadow.light = i;
        shadow.key = light.path.empty() ? "camera light" : light.path;
        if (shadows.mode != ShadowMode::Off) fitView(shadow, light, shadows, strands, meshes, mapped);
        planStrandLines(shadow, shadows, shadows.strandLinesSetting, strands.casters.maxWidth);
        shadows.lights.push_back(std::move(shadow));
    }
    checkSampledDomesShadowed(shadows, lights, strands);
    planVolumeBackScattering(shadows, settings, strands);
    planVolumeDomeOcclusion(shadows, lights.lights, strands);
    planVolumeGrid(shadows, strands);
    planShadowSampling(shadows, shadows.samplingSetting, strands);
    if (shadows.mode == ShadowMode::DeepOpacity && settings.domeShadowFilter == DomeShadowFilter::Mipmap)
        for (size_t i = 0; i < lights.lights.lights.size() && !shadows.convolvedOpacity; ++i)
            shadows.convolvedOpacity = lights.lights.lights[i].isSrbf() && shadows.shadowOf(i) >= 0;
    if (assignment) assignShadowMaps(shadows, *assignment);
    return shadows;
}

size_t shadowMapBudget(int resolution, int layers, int memoryMB) {
    constexpr size_t kGuaranteedArrayLayers = 2048;  // GL 4.5's minimum GL_MAX_ARRAY_TEXTURE_LAYERS
    const size_t targets = size_t((layers + 3) / 4);
    const double bytesPerMap = double(resolution) * double(resolution) * (4.0 + 4.0 + 8.0 * double(targets));
    const double fitting = std::floor(double(memoryMB) * 1024.0 * 1024.0 / bytesPerMap);
    const size_t limit = std::min(kGuaranteedArrayLayers / targets, size_t(std::min(fitting, 1e9)));
    if (limit == 0) return 0;
    size_t maps = 1;
    while (maps * 2 <= limit) maps *= 2;
    return maps;
}

}  // namespace hdhair
