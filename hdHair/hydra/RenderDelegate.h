#pragma once
// HdHairRenderDelegate: hdHair's Hydra render delegate. It supports
// basisCurves (drawn) and mesh (kept for occlusion) rprims; camera, material
// and light sprims (distant, sphere, rect, disk, dome, and simpleLight so
// hosts add their camera light); renderBuffer bprims. Every engine setting is
// a Hydra render setting with the same name as hdhair-record's --setting.

#include <memory>

#include "pxr/imaging/hd/renderDelegate.h"
#include "pxr/imaging/hd/resourceRegistry.h"

#include "hdHair/plan/RenderSettings.h"

PXR_NAMESPACE_OPEN_SCOPE

class HdHairRenderParam;

class HdHairRenderDelegate final : public HdRenderDelegate {
public:
    HdHairRenderDelegate();
    explicit HdHairRenderDelegate(HdRenderSettingsMap const& settingsMap);
    ~HdHairRenderDelegate() override;

    TfTokenVector const& GetSupportedRprimTypes() const override;
    TfTokenVector const& GetSupportedSprimTypes() const override;
    TfTokenVector const& GetSupportedBprimTypes() const override;
    HdRenderParam* GetRenderParam() const override;
    HdResourceRegistrySharedPtr GetResourceRegistry() const override { return _resourceRegistry; }

    HdRenderSettingDescriptorList GetRenderSettingDescriptors() const override;
    HdAovDescriptor GetDefaultAovDescriptor(TfToken const& name) const override;
    VtDictionary GetRenderStats() const override;

    HdRenderPassSharedPtr CreateRenderPass(HdRenderIndex* index, HdRprimCollection const& collection) override;
    HdInstancer* CreateInstancer(HdSceneDelegate* delegate, SdfPath const& id) override;
    void DestroyInstancer(HdInstancer* instancer) override;
    HdRprim* CreateRprim(TfToken const& typeId, SdfPath const& rprimId) override;
    void DestroyRprim(HdRprim* rprim) override;
    HdSprim* CreateSprim(TfToken const& typeId, SdfPath const& sprimId) override;
    HdSprim* CreateFallbackSprim(TfToken const& typeId) override;
    void DestroySprim(HdSprim* sprim) override;
    HdBprim* CreateBprim(TfToken const& typeId, SdfPath const& bprimId) override;
    HdBprim* CreateFallbackBprim(TfToken const& typeId) override;
    void DestroyBprim(HdBprim* bprim) override;
    void CommitResources(HdChangeTracker*) override {}

    // The engine's settings as the host has set them. A value the engine
    // rejects (wrong type, out of range) is reported and the default kept.
    hdhair::RenderSettings GetEngineSettings() const;

private:
    void _Initialize();

    HdRenderSettingDescriptorList _settingDescriptors;
    std::shared_ptr<HdHairRenderParam> _renderParam;
    HdResourceRegistrySharedPtr _resourceRegistry;
};

PXR_NAMESPACE_CLOSE_SCOPE
