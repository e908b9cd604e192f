#pragma once
// How a prim's hair is shaded: its model and parameters, from the HdHairAPI
// primvars on the BasisCurves prim (schemas/HdHairAPI) where authored, the
// render settings otherwise. Resolved once per prim and frame; prims with
// equal materials share one (and one set of Marschner tables).
//
// Parameters are per prim in this release: a per-curve or per-vertex
// hdHair primvar contributes the mean of its values, with a warning.

#include <string>

#include "hdHair/shading/KajiyaKay.h"
#include "hdHair/shading/Marschner.h"

namespace hdhair {

class Diagnostics;
class RenderSettings;
struct CurvesPrim;

enum class ShadingModel { Flat = 0, KajiyaKay = 1, Marschner = 2 };

const char* toString(ShadingModel model);

struct HairMaterial {
    ShadingModel model = ShadingModel::KajiyaKay;
    KajiyaKayParameters kajiyaKay;
    MarschnerParameters marschner;  // used when model is Marschner

    bool operator==(const HairMaterial& other) const;
    // Marschner's tables depend only on these: prims that share them share tables.
    bool sharesTablesWith(const HairMaterial& other) const;
};

// Absorption (σ_a) precedence: primvars:hdHair:absorption, then
// hdHair:melanin (with hdHair:melaninRedness), then an authored displayColor
// (its mean, through the colour-to-absorption inversion), then melanin 0.3.
HairMaterial hairMaterialFor(const CurvesPrim& prim, const RenderSettings& settings, Diagnostics& diagnostics);

}  // namespace hdhair
