#pragma once
// How a prim's hair is shaded: its model and parameters, from the HdHairAPI
// primvars on the BasisCurves prim (schemas/HdHairAPI) where authored, the
// render settings otherwise. Resolved once per prim and frame; prims with
// equal materials share one (and one set of Marschner tables).
//
// Parameters may be constant, per curve (uniform) or per vertex (vertex,
// varying): prepareCurves carries the authored ones to the control points
// (hairParameterPrimvars() lists them). Where one varies over a prim, the
// material is that prim's own and the GPU interpolates per-point values
// (hairParameterPoints) along each span, as it does colours.

#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "hdHair/curves/PreparedCurves.h"
#include "hdHair/plan/SettingTokens.h"
#include "hdHair/shading/DualScattering.h"
#include "hdHair/shading/KajiyaKay.h"
#include "hdHair/shading/Marschner.h"

namespace hdhair {

class Diagnostics;
class RenderSettings;
struct CurvesPrim;



// Which of the model's parameters vary over the prim (bit flags).
enum HairParameterVariation : unsigned {
    kNothingVaries = 0,
    kKajiyaKayVaries = 1u << 0,     // Kd, Ks or p
    kAbsorptionVaries = 1u << 1,    // σ_a, or what it comes from (melanin, redness, displayColor)
    kEtaVaries = 1u << 2,           // η
    kLongitudinalVaries = 1u << 3,  // α_R or β_R
};

struct HairMaterial {
    ShadingModel model = ShadingModel::KajiyaKay;
    KajiyaKayParameters kajiyaKay;
    MarschnerParameters marschner;  // used when model is Marschner
    unsigned varies = kNothingVaries;
    // Marschner's azimuthal terms evaluated per fragment instead of read from
    // the material's tables: where absorption or η vary (tables are per
    // material) unless the setting marschner:azimuthal is "tables" (then the
    // prim's mean absorption and η serve), or everywhere with "analytic".
    bool analyticAzimuthal = false;
    // The prim a material with per-point parameters belongs to (such a
    // material is never shared); empty otherwise.
    std::string perPointPrim;
    // Multiple scattering (hdHair/shading/DualScattering.h), Marschner only:
    // with multipleScattering=dualScattering, or auto where the material's
    // multipleScatteringGain reaches kMultipleScatteringBound. From the
    // material's parameters (their means where they vary per point).
    bool dualScattering = false;
    DualScatteringDensities densities;
    float multipleScatteringGain = 0.0f;
    std::string multipleScatteringReason;  // why on or off, for --explain and --stats

    bool perPoint() const { return varies != kNothingVaries; }
    bool usesTables() const { return model == ShadingModel::Marschner && !analyticAzimuthal; }
    bool operator==(const HairMaterial& other) const;
    // Marschner's tables depend only on these: prims that share them share tables.
    bool sharesTablesWith(const HairMaterial& other) const;
    // Likewise the dual-scattering layer (buildDualScatteringTable).
    bool sharesDualScatteringTableWith(const HairMaterial& other) const;
};

// The HdHairAPI primvars prepareCurves carries, each with the value an
// authored primvar that cannot be used (wrong count or type) is repaired to:
// the schema's default.
const std::vector<ShadingPrimvarRequest>& hairParameterPrimvars();

// The prim's material. Absorption (σ_a) precedence: hdHair:absorption, then
// hdHair:melanin (with hdHair:melaninRedness), then an authored displayColor
// (through the colour-to-absorption inversion), then melanin 0.3. Where a
// parameter varies, the material holds its mean over the control points.
HairMaterial hairMaterialFor(const CurvesPrim& prim, const PreparedCurves& prepared, const RenderSettings& settings,
                             Diagnostics& diagnostics);

// The render settings hairMaterialFor reads, as one string: a prim's
// material stays valid while this and the prim's version are unchanged.
std::string hairMaterialSettingsKey(const RenderSettings& settings);

// For a material with perPoint(): two vec4s per control point of `prepared`,
// the layout shaders/include/hairMaterials.glsl interpolates:
//   Kajiya-Kay: (Kd, Ks, p, 0), (0, 0, 0, 0);
//   Marschner:  (σ_a, η), (α_R, β_R, 0, 0) in radians.
// Parameters that do not vary hold the material's value. Melanin and colour
// become σ_a at the control points and σ_a is interpolated: exact at the
// authored vertices, close between them; absorption and the other
// parameters interpolate exactly as authored.
std::vector<glm::vec4> hairParameterPoints(const HairMaterial& material, const PreparedCurves& prepared);

}  // namespace hdhair
