#include "hdHair/hydra/Material.h"

#include <string>

#include "pxr/imaging/hd/sceneDelegate.h"
#include "pxr/imaging/hd/tokens.h"

#include "hdHair/hydra/RenderParam.h"
#include "hdHair/hydra/VtValueConversion.h"
#include "hdHair/scene/MaterialPrim.h"

PXR_NAMESPACE_OPEN_SCOPE

namespace {

std::string stringOf(VtValue const& value) {
    if (value.IsHolding<TfToken>()) return value.UncheckedGet<TfToken>().GetString();
    if (value.IsHolding<std::string>()) return value.UncheckedGet<std::string>();
    return std::string();
}

// A UsdPreviewSurface input as hdHair reads it. UsdImaging has already
// resolved Material interface inputs into node parameters; `defaults` stays
// for an unauthored input.
hdhair::MaterialInput readInput(HdMaterialNetwork2 const& network, HdMaterialNode2 const& surface,
                                TfToken const& name, hdhair::MaterialInput defaults) {
    auto connection = surface.inputConnections.find(name);
    if (connection != surface.inputConnections.end() && !connection->second.empty()) {
        auto upstream = network.nodes.find(connection->second.front().upstreamNode);
        if (upstream == network.nodes.end()) return defaults;
        HdMaterialNode2 const& node = upstream->second;
        if (TfStringStartsWith(node.nodeTypeId.GetString(), "UsdPrimvarReader_")) {
            hdhair::MaterialInput input{hdhair::MaterialInput::Source::Primvar, {}, {}, {}};
            auto varname = node.parameters.find(TfToken("varname"));
            if (varname != node.parameters.end()) input.primvar = stringOf(varname->second);
            auto fallback = node.parameters.find(TfToken("fallback"));
            HdHairFloats floats;
            if (fallback != node.parameters.end() && HdHairToFloats(fallback->second, &floats))
                input.value = floats.values;
            // UsdPrimvarReader's own default fallback is zero.
            if (input.value.empty()) input.value.assign(defaults.value.size(), 0.0f);
            return input;
        }
        return {hdhair::MaterialInput::Source::Unsupported, {}, {}, node.nodeTypeId.GetString()};
    }
    auto parameter = surface.parameters.find(name);
    HdHairFloats floats;
    if (parameter == surface.parameters.end() || !HdHairToFloats(parameter->second, &floats)) return defaults;
    return {hdhair::MaterialInput::Source::Value, floats.values, {}, {}};
}

hdhair::MaterialPrim materialFromResource(SdfPath const& id, VtValue const& resource) {
    hdhair::MaterialPrim material;
    material.path = id.GetString();
    // Empty when the host disables scene materials: no material then.
    if (!resource.IsHolding<HdMaterialNetworkMap>()) return material;
    HdMaterialNetwork2 network = HdConvertToHdMaterialNetwork2(resource.UncheckedGet<HdMaterialNetworkMap>());
    auto terminal = network.terminals.find(HdMaterialTerminalTokens->surface);
    if (terminal == network.terminals.end()) return material;
    auto surface = network.nodes.find(terminal->second.upstreamNode);
    if (surface == network.nodes.end()) return material;
    material.surfaceShaderId = surface->second.nodeTypeId.GetString();
    if (!material.isPreviewSurface()) return material;
    material.diffuseColor = readInput(network, surface->second, TfToken("diffuseColor"), material.diffuseColor);
    material.opacity = readInput(network, surface->second, TfToken("opacity"), material.opacity);
    return material;
}

}  // namespace

void HdHairMaterial::Sync(HdSceneDelegate* sceneDelegate, HdRenderParam* renderParam, HdDirtyBits* dirtyBits) {
    if (*dirtyBits & (DirtyResource | DirtyParams)) {
        hdhair::MaterialPrim material = materialFromResource(GetId(), sceneDelegate->GetMaterialResource(GetId()));
        static_cast<HdHairRenderParam*>(renderParam)->SetMaterial(std::move(material));
    }
    *dirtyBits = Clean;
}

void HdHairMaterial::Finalize(HdRenderParam* renderParam) {
    static_cast<HdHairRenderParam*>(renderParam)->Remove(GetId().GetString());
}

PXR_NAMESPACE_CLOSE_SCOPE
