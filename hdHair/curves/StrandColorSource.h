#pragma once
// Where a strand's colour and opacity come from. Without a material (or with
// one hdHair does not read) they are the prim's displayColor and
// displayOpacity (or primvars:opacity, see opacityPrimvarName). A bound
// UsdPreviewSurface replaces them the way Storm does: its diffuseColor and
// opacity are used, as constants, or as the primvar a UsdPrimvarReader
// connected to them reads. Inputs hdHair cannot evaluate (textures) keep the
// prim's own primvar, with a warning.

#include <string>
#include <vector>

namespace hdhair {

class Diagnostics;
struct CurvesPrim;
struct MaterialPrim;

struct StrandColorSource {
    // One value: a primvar name and the value it resolves to when absent or
    // unusable. When `constant` is not empty the primvar is not read at all.
    struct Channel {
        std::string primvar;
        std::vector<float> fallback;
        std::vector<float> constant;
    };
    Channel color, opacity;
};

// `material` may be nullptr (no binding, or the bound path has no material).
// Reports inputs it cannot use at "<material path>.inputs:<name>".
StrandColorSource strandColorSource(const CurvesPrim& prim, const MaterialPrim* material, Diagnostics& diagnostics);

}  // namespace hdhair
