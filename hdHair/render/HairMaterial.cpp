#include "hdHair/render/HairMaterial.h"

#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/render/RenderSettings.h"
#include "hdHair/scene/CurvesPrim.h"

namespace hdhair {

const char* toString(ShadingModel model) {
    switch (model) {
    case ShadingModel::Flat: return "flat";
    case ShadingModel::KajiyaKay: return "kajiyaKay";
    case ShadingModel::Marschner: return "marschner";
    }
    return "kajiyaKay";
}

bool HairMaterial::sharesTablesWith(const HairMaterial& other) const {
    const MarschnerParameters &a = marschner, &b = other.marschner;
    return a.eta == b.eta && a.sigmaA == b.sigmaA && a.glintScale == b.glintScale &&
           a.causticWidth == b.causticWidth && a.causticFade == b.causticFade && a.causticLimit == b.causticLimit;
}

bool HairMaterial::operator==(const HairMaterial& other) const {
    return model == other.model && kajiyaKay.diffuse == other.kajiyaKay.diffuse &&
           kajiyaKay.specular == other.kajiyaKay.specular && kajiyaKay.shininess == other.kajiyaKay.shininess &&
           marschner.alpha == other.marschner.alpha && marschner.beta == other.marschner.beta &&
           sharesTablesWith(other);
}

namespace {

bool parseModel(const std::string& token, ShadingModel* model) {
    if (token == "flat") *model = ShadingModel::Flat;
    else if (token == "kajiyaKay") *model = ShadingModel::KajiyaKay;
    else if (token == "marschner") *model = ShadingModel::Marschner;
    else return false;
    return true;
}

// The prim's value of a numeric hdHair primvar: its single value, or the mean
// of per-curve/per-vertex values (with a warning: per prim for now).
std::optional<std::vector<float>> primValue(const CurvesPrim& prim, const std::string& name, int tupleSize,
                                            Diagnostics& diagnostics) {
    const Primvar* primvar = prim.findPrimvar(name);
    if (!primvar || primvar->values.empty()) return std::nullopt;
    if (primvar->tupleSize != tupleSize) {
        diagnostics.warn(prim.path + ".primvars:" + name,
                         fmt::format("expected {} component(s) a value, found {}; ignored", tupleSize,
                                     primvar->tupleSize));
        return std::nullopt;
    }
    size_t count = primvar->elementCount();
    std::vector<float> mean(size_t(tupleSize), 0.0f);
    for (size_t e = 0; e < count; ++e)
        for (int c = 0; c < tupleSize; ++c) mean[size_t(c)] += primvar->values[e * size_t(tupleSize) + size_t(c)];
    for (float& value : mean) value /= float(count);
    for (float value : mean)
        if (!std::isfinite(value)) {
            diagnostics.warn(prim.path + ".primvars:" + name, "not finite; ignored");
            return std::nullopt;
        }
    if (count > 1 && name.rfind("hdHair:", 0) == 0)
        diagnostics.warn(prim.path + ".primvars:" + name,
                         fmt::format("{} values: hair parameters are per prim in this release; using their mean",
                                     count));
    return mean;
}

}  // namespace

HairMaterial hairMaterialFor(const CurvesPrim& prim, const RenderSettings& settings, Diagnostics& diagnostics) {
    HairMaterial material;
    parseModel(settings.getToken("shadingModel"), &material.model);
    if (!prim.shadingModel.empty() && !parseModel(prim.shadingModel, &material.model))
        diagnostics.warn(prim.path + ".primvars:hdHair:shadingModel",
                         fmt::format("unknown shading model '{}' (kajiyaKay, marschner or flat); using {}",
                                     prim.shadingModel, toString(material.model)));

    auto scalar = [&](const std::string& name, float fallback) {
        std::optional<std::vector<float>> value = primValue(prim, name, 1, diagnostics);
        return value ? (*value)[0] : fallback;
    };
    material.kajiyaKay.diffuse = scalar("hdHair:kajiyaKay:diffuse", float(settings.getFloat("kajiyaKay:diffuse")));
    material.kajiyaKay.specular = scalar("hdHair:kajiyaKay:specular", float(settings.getFloat("kajiyaKay:specular")));
    material.kajiyaKay.shininess =
        scalar("hdHair:kajiyaKay:shininess", float(settings.getFloat("kajiyaKay:shininess")));

    if (material.model == ShadingModel::Marschner) {
        // Marschner et al. 2003, Table 1 relations between the lobes.
        float alphaR = scalar("hdHair:longitudinalShift", -7.5f) * kMarschnerDegrees;
        float betaR = scalar("hdHair:longitudinalWidth", 7.5f) * kMarschnerDegrees;
        material.marschner = marschnerParametersFromR(alphaR, betaR);
        material.marschner.eta = scalar("hdHair:eta", 1.55f);
        if (auto absorption = primValue(prim, "hdHair:absorption", 3, diagnostics)) {
            material.marschner.sigmaA = glm::max(glm::vec3((*absorption)[0], (*absorption)[1], (*absorption)[2]),
                                                 glm::vec3(0.0f));
        } else if (prim.findPrimvar("hdHair:melanin")) {
            material.marschner.sigmaA =
                marschnerSigmaAFromMelanin(scalar("hdHair:melanin", 0.3f), scalar("hdHair:melaninRedness", 0.0f));
        } else if (auto color = primValue(prim, "displayColor", 3, diagnostics)) {
            material.marschner.sigmaA = marschnerSigmaAFromColor(
                glm::clamp(glm::vec3((*color)[0], (*color)[1], (*color)[2]), glm::vec3(1e-3f), glm::vec3(1.0f)));
        } else {
            material.marschner.sigmaA = marschnerSigmaAFromMelanin(0.3f, 0.0f);
        }
    }
    return material;
}

}  // namespace hdhair
