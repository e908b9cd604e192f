#include "hdHair/hydra/RenderDelegate.h"

#include <stdexcept>

#include "pxr/base/tf/diagnostic.h"
#include "pxr/base/tf/stringUtils.h"
#include "pxr/base/gf/vec4f.h"
#include "pxr/imaging/hd/camera.h"
#include "pxr/imaging/hd/tokens.h"

#include "hdHair/hydra/BasisCurves.h"
#include "hdHair/hydra/Instancer.h"
#include "hdHair/hydra/Light.h"
#include "hdHair/hydra/Material.h"
#include "hdHair/hydra/Mesh.h"
#include "hdHair/hydra/RenderBuffer.h"
#include "hdHair/hydra/RenderParam.h"
#include "hdHair/hydra/RenderPass.h"

PXR_NAMESPACE_OPEN_SCOPE

namespace {

TfTokenVector const kRprimTypes = {HdPrimTypeTokens->basisCurves, HdPrimTypeTokens->mesh};
TfTokenVector const kSprimTypes = {HdPrimTypeTokens->camera,      HdPrimTypeTokens->material,
                                   HdPrimTypeTokens->distantLight, HdPrimTypeTokens->sphereLight,
                                   HdPrimTypeTokens->rectLight,   HdPrimTypeTokens->diskLight,
                                   HdPrimTypeTokens->domeLight,   HdPrimTypeTokens->simpleLight};
TfTokenVector const kBprimTypes = {HdPrimTypeTokens->renderBuffer};

bool isLightType(TfToken const& typeId) {
    return typeId == HdPrimTypeTokens->distantLight || typeId == HdPrimTypeTokens->sphereLight ||
           typeId == HdPrimTypeTokens->rectLight || typeId == HdPrimTypeTokens->diskLight ||
           typeId == HdPrimTypeTokens->domeLight || typeId == HdPrimTypeTokens->simpleLight;
}

// The descriptor's default as the VtValue type usdview builds a widget for:
// float, int, bool, std::string (see the guide's render settings section).
VtValue defaultValueOf(hdhair::SettingDescriptor const& descriptor, hdhair::RenderSettings const& defaults) {
    switch (descriptor.type) {
    case hdhair::SettingType::Float: return VtValue(float(defaults.getFloat(descriptor.name)));
    case hdhair::SettingType::Int: return VtValue(defaults.getInt(descriptor.name));
    case hdhair::SettingType::Bool: return VtValue(defaults.getBool(descriptor.name));
    case hdhair::SettingType::Token: return VtValue(defaults.getToken(descriptor.name));
    }
    return VtValue();
}

// A host's value as the text RenderSettings::set parses.
bool settingText(VtValue const& value, std::string* text) {
    if (value.IsHolding<double>()) *text = TfStringify(value.UncheckedGet<double>());
    else if (value.IsHolding<float>()) *text = TfStringify(value.UncheckedGet<float>());
    else if (value.IsHolding<int>()) *text = TfStringify(value.UncheckedGet<int>());
    else if (value.IsHolding<unsigned int>()) *text = TfStringify(value.UncheckedGet<unsigned int>());
    else if (value.IsHolding<bool>()) *text = value.UncheckedGet<bool>() ? "true" : "false";
    else if (value.IsHolding<std::string>()) *text = value.UncheckedGet<std::string>();
    else if (value.IsHolding<TfToken>()) *text = value.UncheckedGet<TfToken>().GetString();
    else return false;
    return true;
}

}  // namespace

HdHairRenderDelegate::HdHairRenderDelegate() { _Initialize(); }

HdHairRenderDelegate::HdHairRenderDelegate(HdRenderSettingsMap const& settingsMap)
    : HdRenderDelegate(settingsMap) {
    _Initialize();
}

void HdHairRenderDelegate::_Initialize() {
    // The defaults a host sees are those of --complexity low; the complexity a
    // host asks for (usdview's and usdrecord's) arrives per prim as a refine
    // level and scales tessellation unless a setting is set explicitly.
    hdhair::RenderSettings defaults;
    for (hdhair::SettingDescriptor const& descriptor : hdhair::RenderSettings::descriptors())
        _settingDescriptors.push_back(
            {descriptor.description, TfToken(descriptor.name), defaultValueOf(descriptor, defaults)});
    _PopulateDefaultSettings(_settingDescriptors);
    _renderParam = std::make_shared<HdHairRenderParam>();
    _resourceRegistry = std::make_shared<HdResourceRegistry>();
}

HdHairRenderDelegate::~HdHairRenderDelegate() = default;

TfTokenVector const& HdHairRenderDelegate::GetSupportedRprimTypes() const { return kRprimTypes; }
TfTokenVector const& HdHairRenderDelegate::GetSupportedSprimTypes() const { return kSprimTypes; }
TfTokenVector const& HdHairRenderDelegate::GetSupportedBprimTypes() const { return kBprimTypes; }
HdRenderParam* HdHairRenderDelegate::GetRenderParam() const { return _renderParam.get(); }

HdRenderSettingDescriptorList HdHairRenderDelegate::GetRenderSettingDescriptors() const {
    return _settingDescriptors;
}

hdhair::RenderSettings HdHairRenderDelegate::GetEngineSettings() const {
    hdhair::RenderSettings settings;
    for (hdhair::SettingDescriptor const& descriptor : hdhair::RenderSettings::descriptors()) {
        auto it = _settingsMap.find(TfToken(descriptor.name));
        if (it == _settingsMap.end()) continue;
        std::string text;
        if (!settingText(it->second, &text)) {
            TF_WARN("hdHair: render setting '%s' has a value of type %s; keeping its default",
                    descriptor.name.c_str(), it->second.GetTypeName().c_str());
            continue;
        }
        // The default as the host echoes it back is not an explicit choice:
        // it must not pin tessellation against the host's complexity.
        if (it->second == defaultValueOf(descriptor, hdhair::RenderSettings{})) continue;
        try {
            settings.set(descriptor.name, text);
        } catch (std::invalid_argument const& error) {
            TF_WARN("hdHair: %s; keeping its default", error.what());
        }
    }
    return settings;
}

HdAovDescriptor HdHairRenderDelegate::GetDefaultAovDescriptor(TfToken const& name) const {
    // Colour is linear and pre-multiplied, in Storm's format; depth is window
    // depth; ids are -1 where nothing was drawn.
    if (name == HdAovTokens->color) return HdAovDescriptor(HdFormatFloat16Vec4, false, VtValue(GfVec4f(0.0f)));
    if (name == HdAovTokens->depth) return HdAovDescriptor(HdFormatFloat32, false, VtValue(1.0f));
    if (name == HdAovTokens->primId || name == HdAovTokens->instanceId || name == HdAovTokens->elementId)
        return HdAovDescriptor(HdFormatInt32, false, VtValue(-1));
    return HdAovDescriptor();
}

VtDictionary HdHairRenderDelegate::GetRenderStats() const {
    VtDictionary stats;
    stats["hdHairWarnings"] = VtValue(int(_renderParam->GetDiagnostics().warningCount()));
    // How often each prim was synced: shows (and lets tests check) that an
    // edit re-syncs only the prim it touched.
    VtDictionary syncs;
    for (auto const& [path, count] : _renderParam->GetSyncCounts()) syncs[path] = VtValue(int(count));
    stats["hdHairSyncCounts"] = VtValue(syncs);
    // The last full frame's passes, timings and plan (hdHair/render/RenderStats.h);
    // previews are not reported there.
    auto [frameStats, plan] = _renderParam->GetLastFrame();
    stats["hdHairFrameStats"] = VtValue(frameStats);
    stats["hdHairPlan"] = VtValue(plan);
    // Progressive rendering (RenderPass.h): what the buffers hold now,
    // whether a view is being rendered, how many previews and full frames
    // were finished and cancelled, and the last preview's pixels and curves.
    HdHairRenderParam::Progress const progress = _renderParam->GetProgress();
    stats["hdHairShownFrame"] = VtValue(progress.shown);
    stats["hdHairFrameError"] = VtValue(progress.error);
    stats["hdHairRendering"] = VtValue(progress.rendering);
    stats["hdHairPreviews"] = VtValue(int(progress.previews));
    stats["hdHairFullFrames"] = VtValue(int(progress.finals));
    stats["hdHairCancelledFrames"] = VtValue(int(progress.cancelled));
    stats["hdHairPreviewPixelDivisor"] = VtValue(progress.previewPixelDivisor);
    stats["hdHairPreviewCurveStride"] = VtValue(progress.previewCurveStride);
    return stats;
}

HdRenderPassSharedPtr HdHairRenderDelegate::CreateRenderPass(HdRenderIndex* index,
                                                             HdRprimCollection const& collection) {
    return std::make_shared<HdHairRenderPass>(index, collection, this, _renderParam.get());
}

HdInstancer* HdHairRenderDelegate::CreateInstancer(HdSceneDelegate* delegate, SdfPath const& id) {
    return new HdHairInstancer(delegate, id);
}

void HdHairRenderDelegate::DestroyInstancer(HdInstancer* instancer) { delete instancer; }

HdRprim* HdHairRenderDelegate::CreateRprim(TfToken const& typeId, SdfPath const& rprimId) {
    if (typeId == HdPrimTypeTokens->basisCurves) return new HdHairBasisCurves(rprimId);
    if (typeId == HdPrimTypeTokens->mesh) return new HdHairMesh(rprimId);
    TF_CODING_ERROR("hdHair: unknown rprim type %s", typeId.GetText());
    return nullptr;
}

void HdHairRenderDelegate::DestroyRprim(HdRprim* rprim) { delete rprim; }

HdSprim* HdHairRenderDelegate::CreateSprim(TfToken const& typeId, SdfPath const& sprimId) {
    if (typeId == HdPrimTypeTokens->camera) return new HdCamera(sprimId);
    if (typeId == HdPrimTypeTokens->material) return new HdHairMaterial(sprimId);
    if (isLightType(typeId)) return new HdHairLight(sprimId, typeId);
    TF_CODING_ERROR("hdHair: unknown sprim type %s", typeId.GetText());
    return nullptr;
}

HdSprim* HdHairRenderDelegate::CreateFallbackSprim(TfToken const& typeId) {
    // Fallback sprims have an empty path and are never synced by a scene
    // delegate; they exist so that the render index always has one per type.
    return CreateSprim(typeId, SdfPath::EmptyPath());
}

void HdHairRenderDelegate::DestroySprim(HdSprim* sprim) { delete sprim; }

HdBprim* HdHairRenderDelegate::CreateBprim(TfToken const& typeId, SdfPath const& bprimId) {
    if (typeId == HdPrimTypeTokens->renderBuffer) return new HdHairRenderBuffer(bprimId);
    TF_CODING_ERROR("hdHair: unknown bprim type %s", typeId.GetText());
    return nullptr;
}

HdBprim* HdHairRenderDelegate::CreateFallbackBprim(TfToken const& typeId) {
    return CreateBprim(typeId, SdfPath::EmptyPath());
}

void HdHairRenderDelegate::DestroyBprim(HdBprim* bprim) { delete bprim; }

PXR_NAMESPACE_CLOSE_SCOPE
