#pragma once
// The values of every token setting, as enums, each with its table of names
// (base/TokenTable.h): the one place a setting's values are spelt. The
// descriptors (RenderSettings.cpp) list their tokens from these tables, in
// the tables' order, so --help-settings, docs/settings.md, Hydra's render
// settings and --stats print what parses here. Planners and passes compare
// the enums, never text.

#include <array>

#include "hdHair/base/TokenTable.h"

namespace hdhair {

// quality: a named set of settings (QualityPresets.h).
enum class Quality { Preview, Default, High, Reference };
template <>
struct TokenTable<Quality> {
    static constexpr std::array<TokenName<Quality>, 4> names{{{Quality::Preview, "preview"},
                                                              {Quality::Default, "default"},
                                                              {Quality::High, "high"},
                                                              {Quality::Reference, "reference"}}};
};

// tessellation: how finely each curve span is cut.
enum class Tessellation { ScreenError, ProjectedLength };
template <>
struct TokenTable<Tessellation> {
    static constexpr std::array<TokenName<Tessellation>, 2> names{
        {{Tessellation::ScreenError, "screenError"}, {Tessellation::ProjectedLength, "projectedLength"}}};
};

// transparency: the compositing path asked for, and the one planned
// (TransparencyPlanner.h; the strands may not need blending at all).
enum class TransparencyPath { Opaque, BinSorted, Exact, Unsorted };
template <>
struct TokenTable<TransparencyPath> {
    static constexpr std::array<TokenName<TransparencyPath>, 4> names{{{TransparencyPath::BinSorted, "binSorted"},
                                                                       {TransparencyPath::Exact, "exact"},
                                                                       {TransparencyPath::Unsorted, "unsorted"},
                                                                       {TransparencyPath::Opaque, "opaque"}}};
};

// exactOverflow: what exact transparency does over exactMemoryMB.
enum class ExactOverflow { FallBack, Fail };
template <>
struct TokenTable<ExactOverflow> {
    static constexpr std::array<TokenName<ExactOverflow>, 2> names{
        {{ExactOverflow::FallBack, "fallBack"}, {ExactOverflow::Fail, "fail"}}};
};

// strandRaster: who rasterises the blended strands, as asked
// (StrandRasterPlanner.h decides StrandRaster from it).
enum class StrandRasterSetting { Hardware, Compute, Auto };
template <>
struct TokenTable<StrandRasterSetting> {
    static constexpr std::array<TokenName<StrandRasterSetting>, 3> names{{{StrandRasterSetting::Hardware, "hardware"},
                                                                          {StrandRasterSetting::Compute, "compute"},
                                                                          {StrandRasterSetting::Auto, "auto"}}};
};

// shadingModel, and a prim's primvars:hdHair:shadingModel. The values are
// the shaders' model ids (HairMaterialTable's modelAndLayer.x).
enum class ShadingModel { Flat = 0, KajiyaKay = 1, Marschner = 2 };
template <>
struct TokenTable<ShadingModel> {
    static constexpr std::array<TokenName<ShadingModel>, 3> names{{{ShadingModel::KajiyaKay, "kajiyaKay"},
                                                                   {ShadingModel::Marschner, "marschner"},
                                                                   {ShadingModel::Flat, "flat"}}};
};

// marschner:azimuthal: Marschner's azimuthal terms from tables or per fragment.
enum class MarschnerAzimuthal { Auto, Tables, Analytic };
template <>
struct TokenTable<MarschnerAzimuthal> {
    static constexpr std::array<TokenName<MarschnerAzimuthal>, 3> names{{{MarschnerAzimuthal::Auto, "auto"},
                                                                         {MarschnerAzimuthal::Tables, "tables"},
                                                                         {MarschnerAzimuthal::Analytic, "analytic"}}};
};

// multipleScattering: dual scattering on Marschner prims.
enum class MultipleScattering { Auto, DualScattering, Off };
template <>
struct TokenTable<MultipleScattering> {
    static constexpr std::array<TokenName<MultipleScattering>, 3> names{
        {{MultipleScattering::Auto, "auto"},
         {MultipleScattering::DualScattering, "dualScattering"},
         {MultipleScattering::Off, "off"}}};
};

// multipleScattering:localTerm: what dual scattering's local back
// scattering assumes lies behind each fibre.
enum class DualScatteringLocalTerm { DensityVolume, Constant };
template <>
struct TokenTable<DualScatteringLocalTerm> {
    static constexpr std::array<TokenName<DualScatteringLocalTerm>, 2> names{
        {{DualScatteringLocalTerm::DensityVolume, "densityVolume"}, {DualScatteringLocalTerm::Constant, "constant"}}};
};

// shadowMode: how lights shadow the hair.
enum class ShadowMode { Auto, DeepOpacity, Volume, Reference, Off };
template <>
struct TokenTable<ShadowMode> {
    static constexpr std::array<TokenName<ShadowMode>, 5> names{{{ShadowMode::Auto, "auto"},
                                                                  {ShadowMode::DeepOpacity, "deepOpacity"},
                                                                  {ShadowMode::Volume, "volume"},
                                                                  {ShadowMode::Reference, "reference"},
                                                                  {ShadowMode::Off, "off"}}};
};

// shadowStrandLines: how deep opacity maps draw the strands.
enum class ShadowStrandLines { Auto, Compute, Drawn, Tessellated, Off };
template <>
struct TokenTable<ShadowStrandLines> {
    static constexpr std::array<TokenName<ShadowStrandLines>, 5> names{{{ShadowStrandLines::Auto, "auto"},
                                                                        {ShadowStrandLines::Compute, "compute"},
                                                                        {ShadowStrandLines::Drawn, "drawn"},
                                                                        {ShadowStrandLines::Tessellated, "tessellated"},
                                                                        {ShadowStrandLines::Off, "off"}}};
};

// shadowLayerSpacing: where the deep opacity layers' boundaries lie (DeepOpacityLayers.h).
enum class ShadowLayerSpacing { Linear, Uniform };
template <>
struct TokenTable<ShadowLayerSpacing> {
    static constexpr std::array<TokenName<ShadowLayerSpacing>, 2> names{
        {{ShadowLayerSpacing::Linear, "linear"}, {ShadowLayerSpacing::Uniform, "uniform"}}};
};

// shadowFilter: the shadow lookup's filter.
enum class ShadowFilter { Nearest, Bilinear };
template <>
struct TokenTable<ShadowFilter> {
    static constexpr std::array<TokenName<ShadowFilter>, 2> names{
        {{ShadowFilter::Nearest, "nearest"}, {ShadowFilter::Bilinear, "bilinear"}}};
};

// shadowSampling: where deep opacity maps are looked up.
enum class ShadowSampling { Auto, Vertex, Fragment };
template <>
struct TokenTable<ShadowSampling> {
    static constexpr std::array<TokenName<ShadowSampling>, 3> names{
        {{ShadowSampling::Auto, "auto"}, {ShadowSampling::Vertex, "vertex"}, {ShadowSampling::Fragment, "fragment"}}};
};

// domeLighting: how DomeLights light the frame (DomeLighting.h).
enum class DomeLightingMode { Srbf, Ambient, Sampled };
template <>
struct TokenTable<DomeLightingMode> {
    static constexpr std::array<TokenName<DomeLightingMode>, 3> names{{{DomeLightingMode::Srbf, "srbf"},
                                                                       {DomeLightingMode::Ambient, "ambient"},
                                                                       {DomeLightingMode::Sampled, "sampled"}}};
};

// domeShadowFilter: how an SRBF light's shadow widens with depth.
enum class DomeShadowFilter { Taps, Mipmap };
template <>
struct TokenTable<DomeShadowFilter> {
    static constexpr std::array<TokenName<DomeShadowFilter>, 2> names{
        {{DomeShadowFilter::Taps, "taps"}, {DomeShadowFilter::Mipmap, "mipmap"}}};
};

// cameraLight: light from the camera.
enum class CameraLightSetting { Auto, On, Off };
template <>
struct TokenTable<CameraLightSetting> {
    static constexpr std::array<TokenName<CameraLightSetting>, 3> names{
        {{CameraLightSetting::Auto, "auto"}, {CameraLightSetting::On, "on"}, {CameraLightSetting::Off, "off"}}};
};

// cameraLightShadows: whether hdHair's camera light casts shadows.
enum class CameraLightShadows { Off, On };
template <>
struct TokenTable<CameraLightShadows> {
    static constexpr std::array<TokenName<CameraLightShadows>, 2> names{
        {{CameraLightShadows::Off, "off"}, {CameraLightShadows::On, "on"}}};
};

// drawBatching: how strand draws are cut (gl::PatchBatching).
enum class DrawBatching { Auto, On, Off };
template <>
struct TokenTable<DrawBatching> {
    static constexpr std::array<TokenName<DrawBatching>, 3> names{
        {{DrawBatching::Auto, "auto"}, {DrawBatching::On, "on"}, {DrawBatching::Off, "off"}}};
};

// framing: how a camera is made when none is given (CameraView.h, frameBounds).
enum class FramingStyle {
    // Exactly usdrecord's camera (UsdAppUtilsFrameRecorder,
    // _ComputeCameraToFrameStage in pxr/usdImaging/usdAppUtils/frameRecorder.cpp):
    // fits the half-diagonal of the bounds' face across the view to HALF THE
    // WIDTH of the default lens's field of view. Bounds taller than about
    // 1.07 times their width are therefore cut at the top and bottom, as in
    // usdrecord's own images.
    UsdRecord,
    // The same camera direction and lens, moved back just enough that all
    // eight corners of the bounds are inside the image.
    FitAll,
};
template <>
struct TokenTable<FramingStyle> {
    static constexpr std::array<TokenName<FramingStyle>, 2> names{
        {{FramingStyle::FitAll, "fitAll"}, {FramingStyle::UsdRecord, "usdrecord"}}};
};

}  // namespace hdhair
