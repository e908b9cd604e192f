#include "hdHair/hydra/Light.h"

#include "pxr/base/gf/vec3d.h"
#include "pxr/base/gf/vec3f.h"
#include "pxr/usd/sdf/assetPath.h"
#include "pxr/imaging/hd/sceneDelegate.h"
#include "pxr/imaging/hd/tokens.h"

#include "hdHair/hydra/HydraCamera.h"
#include "hdHair/hydra/HydraLights.h"
#include "hdHair/hydra/RenderParam.h"
#include "hdHair/hydra/VtValueConversion.h"

PXR_NAMESPACE_OPEN_SCOPE

namespace {

// HdLightTokens->textureFile and textureFormat, for a dome light.
hdhair::hydra::HydraDomeTexture domeTexture(HdSceneDelegate* sceneDelegate, SdfPath const& id) {
    hdhair::hydra::HydraDomeTexture texture;
    VtValue file = sceneDelegate->GetLightParamValue(id, HdLightTokens->textureFile);
    if (file.IsHolding<SdfAssetPath>()) {
        SdfAssetPath const& asset = file.UncheckedGet<SdfAssetPath>();
        texture.file = asset.GetResolvedPath().empty() ? asset.GetAssetPath() : asset.GetResolvedPath();
    }
    VtValue format = sceneDelegate->GetLightParamValue(id, HdLightTokens->textureFormat);
    if (format.IsHolding<TfToken>()) texture.format = format.UncheckedGet<TfToken>().GetString();
    return texture;
}

hdhair::LightType engineLightType(TfToken const& lightType) {
    if (lightType == HdPrimTypeTokens->sphereLight) return hdhair::LightType::Sphere;
    if (lightType == HdPrimTypeTokens->rectLight) return hdhair::LightType::Rect;
    if (lightType == HdPrimTypeTokens->diskLight) return hdhair::LightType::Disk;
    if (lightType == HdPrimTypeTokens->domeLight) return hdhair::LightType::Dome;
    return hdhair::LightType::Distant;  // distantLight and simpleLight
}

}  // namespace

HdHairLight::HdHairLight(SdfPath const& id, TfToken const& lightType) : HdLight(id), _lightType(lightType) {}

HdDirtyBits HdHairLight::GetInitialDirtyBitsMask() const { return AllDirty; }

void HdHairLight::Sync(HdSceneDelegate* sceneDelegate, HdRenderParam* renderParam, HdDirtyBits* dirtyBits) {
    SdfPath const& id = GetId();
    if (*dirtyBits & (DirtyTransform | DirtyParams)) {
        // Hosts mark their own lights (usdview's and usdrecord's camera
        // light) with a GlfSimpleLight in "params"; hdHair does not link glf,
        // so it recognises the type by name.
        VtValue hostParams = sceneDelegate->GetLightParamValue(id, HdLightTokens->params);
        bool hostCameraLight = _lightType == HdPrimTypeTokens->simpleLight ||
                               (_lightType != HdPrimTypeTokens->domeLight &&
                                hostParams.GetTypeName() == "GlfSimpleLight");
        hdhair::hydra::LightParameterLookup lookup =
            [&](std::string const& name) -> std::optional<std::vector<double>> {
            HdHairFloats floats;
            if (!HdHairToFloats(sceneDelegate->GetLightParamValue(id, TfToken(name)), &floats)) return std::nullopt;
            return std::vector<double>(floats.values.begin(), floats.values.end());
        };
        GfMatrix4d toWorld = sceneDelegate->GetTransform(id);
        // DomeLight_1's poleAxis turns only the dome: UsdImaging hands the
        // turn over as domeOffset, applied before the prim's transform as
        // Storm applies it (HdStLight::Sync).
        if (_lightType == HdPrimTypeTokens->domeLight) {
            VtValue domeOffset = sceneDelegate->GetLightParamValue(id, HdLightTokens->domeOffset);
            if (domeOffset.IsHolding<GfMatrix4d>()) toWorld = domeOffset.UncheckedGet<GfMatrix4d>() * toWorld;
        }
        hdhair::LightPrim light = hdhair::hydra::lightFromHydra(
            id.GetString(), engineLightType(_lightType), hostCameraLight, lookup,
            hdhair::hydra::matrixFromGf(toWorld.data()),
            _lightType == HdPrimTypeTokens->domeLight ? domeTexture(sceneDelegate, id)
                                                      : hdhair::hydra::HydraDomeTexture());
        light.visible = sceneDelegate->GetVisible(id);
        static_cast<HdHairRenderParam*>(renderParam)->SetLight(std::move(light));
    }
    *dirtyBits = Clean;
}

void HdHairLight::Finalize(HdRenderParam* renderParam) {
    static_cast<HdHairRenderParam*>(renderParam)->Remove(GetId().GetString());
}

PXR_NAMESPACE_CLOSE_SCOPE
