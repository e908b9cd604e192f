#include "hdHair/plan/HairMaterial.h"

#include <algorithm>
#include <cstddef>
#include <optional>

#include <fmt/format.h>
#include <glm/common.hpp>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/plan/RenderSettings.h"
#include "hdHair/scene/CurvesPrim.h"

namespace hdhair {

bool HairMaterial::sharesTablesWith(const HairMaterial& other) const {
    const MarschnerParameters &a = marschner, &b = other.marschner;
    return a.eta == b.eta && a.sigmaA == b.sigmaA && a.glintScale == b.glintScale &&
           a.causticWidth == b.causticWidth && a.causticFade == b.causticFade && a.causticLimit == b.causticLimit;
}

bool HairMaterial::sharesDualScatteringTableWith(const HairMaterial& other) const {
    return sharesTablesWith(other) && marschner.alpha == other.marschner.alpha &&
           marschner.beta == other.marschner.beta && densities.backward == other.densities.backward;
}

bool HairMaterial::operator==(const HairMaterial& other) const {
    return model == other.model && kajiyaKay.diffuse == other.kajiyaKay.diffuse &&
           kajiyaKay.specular == other.kajiyaKay.specular && kajiyaKay.shininess == other.kajiyaKay.shininess &&
           marschner.alpha == other.marschner.alpha && marschner.beta == other.marschner.beta &&
           sharesTablesWith(other) && varies == other.varies && analyticAzimuthal == other.analyticAzimuthal &&
           perPointPrim == other.perPointPrim && dualScattering == other.dualScattering &&
           densities.forward == other.densities.forward && densities.backward == other.densities.backward;
}

namespace {

// Schema defaults (schemas/HdHairAPI/schema.usda), in the primvars' units.
constexpr float kDefaultMelanin = 0.3f;
constexpr float kDefaultShiftDegrees = -7.5f;  // Marschner 2003 Table 1
constexpr float kDefaultWidthDegrees = 7.5f;
constexpr float kDefaultEta = 1.55f;

// The hair parameters at one place: the whole prim (where a primvar varies,
// the mean of its control-point values) or one control point.
class HairParameterSource {
public:
    HairParameterSource(const PreparedCurves& prepared, std::optional<size_t> point)
        : prepared_(prepared), point_(point) {}

    bool authored(const std::string& name) const { return prepared_.findShadingPrimvar(name) != nullptr; }
    bool varies(const std::string& name) const {
        const PreparedShadingPrimvar* primvar = prepared_.findShadingPrimvar(name);
        return primvar && primvar->varying;
    }
    std::optional<float> scalar(const std::string& name) const {
        std::optional<glm::vec4> value = tuple(name);
        return value ? std::optional<float>(value->x) : std::nullopt;
    }
    std::optional<glm::vec3> vector3(const std::string& name) const {
        std::optional<glm::vec4> value = tuple(name);
        return value ? std::optional<glm::vec3>(glm::vec3(*value)) : std::nullopt;
    }

    // The strand colour, when authored (hair colour as absorption's source).
    bool colorAuthored() const { return prepared_.colorAuthored; }
    bool colorVaries() const {
        const std::vector<StrandControlPoint>& points = prepared_.controlPoints;
        return std::any_of(points.begin(), points.end(),
                           [&](const StrandControlPoint& p) { return p.color != points.front().color; });
    }
    glm::vec3 color() const {
        const std::vector<StrandControlPoint>& points = prepared_.controlPoints;
        if (points.empty()) return glm::vec3(0.5f);
        if (point_) return points[*point_].color;
        glm::dvec3 sum(0.0);
        for (const StrandControlPoint& p : points) sum += glm::dvec3(p.color);
        return glm::vec3(sum / double(points.size()));
    }

private:
    std::optional<glm::vec4> tuple(const std::string& name) const {
        const PreparedShadingPrimvar* primvar = prepared_.findShadingPrimvar(name);
        if (!primvar) return std::nullopt;
        const size_t tupleSize = size_t(std::min(primvar->tupleSize, 4));
        glm::vec4 value(0.0f);
        if (!primvar->varying || point_) {
            const float* element = primvar->at(point_.value_or(0));
            for (size_t c = 0; c < tupleSize; ++c) value[int(c)] = element[c];
            return value;
        }
        const size_t count = prepared_.controlPoints.size();
        if (count == 0) return std::nullopt;
        glm::dvec4 sum(0.0);
        for (size_t k = 0; k < count; ++k)
            for (size_t c = 0; c < tupleSize; ++c) sum[int(c)] += primvar->at(k)[c];
        return glm::vec4(sum / double(count));
    }

    const PreparedCurves& prepared_;
    std::optional<size_t> point_;
};

// Overrides the parameters the source authors; the rest keep their values.
void applyHairParameters(const HairParameterSource& at, ShadingModel model, KajiyaKayParameters& kajiyaKay,
                         MarschnerParameters& marschner) {
    if (model == ShadingModel::KajiyaKay) {
        kajiyaKay.diffuse = at.scalar("hdHair:kajiyaKay:diffuse").value_or(kajiyaKay.diffuse);
        kajiyaKay.specular = at.scalar("hdHair:kajiyaKay:specular").value_or(kajiyaKay.specular);
        kajiyaKay.shininess = at.scalar("hdHair:kajiyaKay:shininess").value_or(kajiyaKay.shininess);
    }
    if (model != ShadingModel::Marschner) return;
    // Marschner et al. 2003, Table 1 relations between the lobes.
    std::optional<float> shift = at.scalar("hdHair:longitudinalShift");
    std::optional<float> width = at.scalar("hdHair:longitudinalWidth");
    if (shift || width) {
        MarschnerParameters lobes =
            marschnerParametersFromR(shift ? *shift * kMarschnerDegrees : marschner.alpha.x,
                                     width ? *width * kMarschnerDegrees : marschner.beta.x);
        marschner.alpha = lobes.alpha;
        marschner.beta = lobes.beta;
    }
    marschner.eta = at.scalar("hdHair:eta").value_or(marschner.eta);
    if (std::optional<glm::vec3> absorption = at.vector3("hdHair:absorption")) {
        // Not clamped here: control points outside a curve (a linear span's
        // 2a - b) may be negative so that interpolation stays linear; the
        // model counts σ_a < 0 as 0 where it evaluates.
        marschner.sigmaA = *absorption;
    } else if (at.authored("hdHair:melanin")) {
        marschner.sigmaA = marschnerSigmaAFromMelanin(at.scalar("hdHair:melanin").value_or(kDefaultMelanin),
                                                      at.scalar("hdHair:melaninRedness").value_or(0.0f));
    } else if (at.colorAuthored()) {
        marschner.sigmaA = marschnerSigmaAFromColor(glm::clamp(at.color(), glm::vec3(1e-3f), glm::vec3(1.0f)));
    }
}

// Which of the model's parameters vary over the prim.
unsigned variationOf(const HairParameterSource& prim, ShadingModel model) {
    unsigned varies = kNothingVaries;
    if (model == ShadingModel::KajiyaKay &&
        (prim.varies("hdHair:kajiyaKay:diffuse") || prim.varies("hdHair:kajiyaKay:specular") ||
         prim.varies("hdHair:kajiyaKay:shininess")))
        varies |= kKajiyaKayVaries;
    if (model != ShadingModel::Marschner) return varies;
    if (prim.varies("hdHair:longitudinalShift") || prim.varies("hdHair:longitudinalWidth"))
        varies |= kLongitudinalVaries;
    if (prim.varies("hdHair:eta")) varies |= kEtaVaries;
    bool absorptionVaries;
    if (prim.authored("hdHair:absorption"))
        absorptionVaries = prim.varies("hdHair:absorption");
    else if (prim.authored("hdHair:melanin"))
        absorptionVaries = prim.varies("hdHair:melanin") || prim.varies("hdHair:melaninRedness");
    else
        absorptionVaries = prim.colorAuthored() && prim.colorVaries();
    if (absorptionVaries) varies |= kAbsorptionVaries;
    return varies;
}

}  // namespace

const std::vector<ShadingPrimvarRequest>& hairParameterPrimvars() {
    // Ranges from the schema's docs (schemas/HdHairAPI/schema.usda); where
    // it gives none beyond "> 0", the bounds that keep the model finite:
    // eta above 1 (at 1 a fibre refracts nothing), lobe shifts and widths
    // within a right angle, weights and the exponent as the settings allow.
    static const std::vector<ShadingPrimvarRequest> requests{
        {"hdHair:melanin", {kDefaultMelanin}, 0.0f, 1.0f},
        {"hdHair:melaninRedness", {0.0f}, 0.0f, 1.0f},
        {"hdHair:absorption", {0.0f, 0.0f, 0.0f}, 0.0f, 1e6f},  // an unusable absorption means no absorption
        {"hdHair:eta", {kDefaultEta}, 1.001f, 2.0f},
        {"hdHair:longitudinalShift", {kDefaultShiftDegrees}, -90.0f, 90.0f},
        {"hdHair:longitudinalWidth", {kDefaultWidthDegrees}, 0.1f, 90.0f},
        {"hdHair:kajiyaKay:diffuse", {KajiyaKayParameters{}.diffuse}, 0.0f, 100.0f},
        {"hdHair:kajiyaKay:specular", {KajiyaKayParameters{}.specular}, 0.0f, 100.0f},
        {"hdHair:kajiyaKay:shininess", {KajiyaKayParameters{}.shininess}, 1.0f, 10000.0f},
    };
    return requests;
}

namespace {

// multipleScattering per material: the setting, and under auto the gain
// against kMultipleScatteringBound; the reason says which.
void decideMultipleScattering(HairMaterial& material, const RenderSettings& settings) {
    const MultipleScattering mode = settings.values().multipleScattering;
    material.densities = {float(settings.values().multipleScatteringForwardDensity),
                          float(settings.values().multipleScatteringBackDensity)};
    if (material.model != ShadingModel::Marschner) {
        material.multipleScatteringReason = fmt::format("{} shading has no multiple scattering", toString(material.model));
        return;
    }
    if (mode == MultipleScattering::Off) {
        material.multipleScatteringReason = "multipleScattering=off";
        return;
    }
    material.multipleScatteringGain = multipleScatteringGain(material.marschner, material.densities);
    const std::string means = material.perPoint() ? " (of its mean parameters: they vary per curve or vertex)" : "";
    if (mode == MultipleScattering::DualScattering) {
        material.dualScattering = true;
        material.multipleScatteringReason =
            fmt::format("multipleScattering=dualScattering (gain {:.3f}{})", material.multipleScatteringGain, means);
        return;
    }
    material.dualScattering = material.multipleScatteringGain >= kMultipleScatteringBound;
    material.multipleScatteringReason =
        fmt::format("auto: gain {:.3f}{} {} the bound {:.2f}: {}", material.multipleScatteringGain, means,
                    material.dualScattering ? "reaches" : "is under", kMultipleScatteringBound,
                    material.dualScattering ? "dual scattering runs"
                                            : "its fibres absorb too much for multiple scattering to show; skipped");
}

}  // namespace

HairMaterial hairMaterialFor(const CurvesPrim& prim, const PreparedCurves& prepared, const RenderSettings& settings,
                             Diagnostics& diagnostics) {
    HairMaterial material;
    material.model = settings.values().shadingModel;
    if (!prim.shadingModel.empty() && !parseToken(prim.shadingModel, &material.model))
        diagnostics.warn(prim.path + ".primvars:hdHair:shadingModel",
                         fmt::format("unknown shading model '{}' ({}); using {}", prim.shadingModel,
                                     tokenChoices<ShadingModel>(), toString(material.model)));

    material.kajiyaKay.diffuse = float(settings.values().kajiyaKayDiffuse);
    material.kajiyaKay.specular = float(settings.values().kajiyaKaySpecular);
    material.kajiyaKay.shininess = float(settings.values().kajiyaKayShininess);
    if (material.model == ShadingModel::Marschner) {
        material.marschner = marschnerParametersFromR(kDefaultShiftDegrees * kMarschnerDegrees,
                                                      kDefaultWidthDegrees * kMarschnerDegrees);
        material.marschner.eta = kDefaultEta;
        material.marschner.sigmaA = marschnerSigmaAFromMelanin(kDefaultMelanin, 0.0f);
    }
    const HairParameterSource wholePrim(prepared, std::nullopt);
    applyHairParameters(wholePrim, material.model, material.kajiyaKay, material.marschner);
    material.varies = variationOf(wholePrim, material.model);
    const MarschnerAzimuthal azimuthal = settings.values().marschnerAzimuthal;
    // Forced tables: absorption and eta stay at their means over the prim.
    if (azimuthal == MarschnerAzimuthal::Tables) material.varies &= ~unsigned(kAbsorptionVaries | kEtaVaries);
    if (material.perPoint()) material.perPointPrim = prim.path;
    material.analyticAzimuthal = material.model == ShadingModel::Marschner &&
                                 (azimuthal == MarschnerAzimuthal::Analytic || (material.varies & (kAbsorptionVaries | kEtaVaries)) != 0);
    decideMultipleScattering(material, settings);
    return material;
}

std::string hairMaterialSettingsKey(const RenderSettings& settings) {
    const SettingValues& values = settings.values();
    return fmt::format("{}|{}|{}|{}|{}|{}|{}|{}", toString(values.shadingModel), values.kajiyaKayDiffuse,
                       values.kajiyaKaySpecular, values.kajiyaKayShininess, toString(values.marschnerAzimuthal),
                       toString(values.multipleScattering),
                       values.multipleScatteringForwardDensity, values.multipleScatteringBackDensity);
}

std::vector<glm::vec4> hairParameterPoints(const HairMaterial& material, const PreparedCurves& prepared) {
    std::vector<glm::vec4> points;
    if (!material.perPoint()) return points;
    const size_t count = prepared.controlPoints.size();
    points.resize(2 * count, glm::vec4(0.0f));
    for (size_t k = 0; k < count; ++k) {
        KajiyaKayParameters kajiyaKay = material.kajiyaKay;
        MarschnerParameters marschner = material.marschner;
        applyHairParameters(HairParameterSource(prepared, k), material.model, kajiyaKay, marschner);
        if (material.model == ShadingModel::KajiyaKay) {
            points[2 * k] = glm::vec4(kajiyaKay.diffuse, kajiyaKay.specular, kajiyaKay.shininess, 0.0f);
        } else if (material.model == ShadingModel::Marschner) {
            points[2 * k] = glm::vec4(marschner.sigmaA, marschner.eta);
            points[2 * k + 1] = glm::vec4(marschner.alpha.x, marschner.beta.x, 0.0f, 0.0f);
        }
    }
    return points;
}

}  // namespace hdhair
