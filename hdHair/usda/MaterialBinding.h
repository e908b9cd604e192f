#pragma once
// UsdShade on the embedded stage: which material a prim is bound to, and
// what its surface says about hair colour (hdHair/scene/MaterialPrim.h), the
// way UsdImaging hands both to Hydra for the preview purpose.
//
// Supported: direct bindings (material:binding:preview, then
// material:binding, on the prim or its nearest ancestor that has one), the
// universal outputs:surface, UsdPreviewSurface's diffuseColor and opacity as
// values, through Material or NodeGraph interface inputs, or from a
// UsdPrimvarReader_*. Not supported: collection-based bindings,
// bindMaterialAs = strongerThanDescendants, render-context outputs
// (outputs:ri:surface...), and shaders other than UsdPreviewSurface (their
// materials leave the prim's colours in place).

#include <optional>
#include <string>

#include "hdHair/scene/MaterialPrim.h"
#include "hdHair/usda/Stage.h"

namespace hdhair::usda {

// The target of the prim's own direct binding for the preview purpose
// (material:binding:preview wins over material:binding); nullopt when the
// prim authors neither, so that the caller inherits its parent's.
std::optional<std::string> directMaterialBinding(const Prim& prim);

// The shader the material's universal outputs:surface connects to; nullptr
// when it connects to nothing or to a prim that does not exist.
const Prim* surfaceShaderOf(const Stage& stage, const Prim& material);

// Reads the Material prim `material` at `time`. Never throws: an input of the
// wrong type reads as its default, and `problem` (when given) says why.
MaterialPrim readMaterial(const Stage& stage, const Prim& material, double time, std::string* problem = nullptr);

}  // namespace hdhair::usda
