#pragma once
// Hydra light sprims in the engine's terms. No pxr here: the sprim hands over
// a function that looks parameters up (GetLightParamValue), so the mapping is
// unit-tested without OpenUSD.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "hdHair/scene/LightPrim.h"

namespace hdhair::hydra {

// Looks up a light parameter by its HdLightTokens name ("intensity",
// "color", "shaping:cone:angle", ...): numbers (bool as 0/1, vectors as their
// components), or nothing when the host has none.
using LightParameterLookup = std::function<std::optional<std::vector<double>>(const std::string& name)>;

// A dome light's texture as the host hands it over: HdLightTokens->textureFile
// (an SdfAssetPath: its resolved path, the authored one when the resolver
// found none; "" for none) and HdLightTokens->textureFormat ("" when the host
// gives none: UsdLux's fallback "automatic" applies).
struct HydraDomeTexture {
    std::string file;
    std::string format;
};

// The engine's light for a Hydra sprim. `type` is the engine's light type;
// Hydra's simpleLight (the camera light usdview and usdrecord add) is passed
// with hostCameraLight = true and becomes a distant light of unit intensity:
// the task controller sets 15000 for non-Storm delegates, a number meant for
// Storm's simple lighting, not UsdLux units.
// `texture` is read for dome lights only.
LightPrim lightFromHydra(const std::string& path, LightType type, bool hostCameraLight,
                         const LightParameterLookup& parameter, const glm::dmat4& lightToWorld,
                         const HydraDomeTexture& texture = {});

}  // namespace hdhair::hydra
