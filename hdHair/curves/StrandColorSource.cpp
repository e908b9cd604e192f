#include "hdHair/curves/StrandColorSource.h"

#include <fmt/format.h>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/curves/PreparedCurves.h"
#include "hdHair/curves/PrimvarResolution.h"
#include "hdHair/scene/CurvesPrim.h"
#include "hdHair/scene/MaterialPrim.h"

namespace hdhair {

namespace {

// A material input over the prim's own channel. `size` is the tuple size the
// channel needs (3 for colour, 1 for opacity).
void applyInput(const MaterialPrim& material, const MaterialInput& input, const char* inputName, size_t size,
                StrandColorSource::Channel& channel, Diagnostics& diagnostics) {
    const std::string where = material.path + ".inputs:" + inputName;
    switch (input.source) {
    case MaterialInput::Source::Value:
        if (input.value.size() != size) {
            diagnostics.warn(where, fmt::format("expected {} value{}, found {}; using the prim's {}", size,
                                                size == 1 ? "" : "s", input.value.size(), channel.primvar));
            return;
        }
        channel.constant = input.value;
        return;
    case MaterialInput::Source::Primvar:
        channel.primvar = input.primvar;
        // Storm's primvar readers give their fallback for a missing primvar.
        if (input.value.size() == size) channel.fallback = input.value;
        return;
    case MaterialInput::Source::Unsupported:
        diagnostics.warn(where, fmt::format("connected to {}, which hdHair does not evaluate; using the prim's {}",
                                            input.connectedTo.empty() ? "a shader" : input.connectedTo,
                                            channel.primvar));
        return;
    }
}

}  // namespace

StrandColorSource strandColorSource(const CurvesPrim& prim, const MaterialPrim* material, Diagnostics& diagnostics) {
    StrandColorSource source;
    source.color = {"displayColor", kFallbackDisplayColor, {}};
    source.opacity = {opacityPrimvarName(prim), kFallbackDisplayOpacity, {}};
    if (!material || !material->isPreviewSurface()) return source;
    applyInput(*material, material->diffuseColor, "diffuseColor", 3, source.color, diagnostics);
    applyInput(*material, material->opacity, "opacity", 1, source.opacity, diagnostics);
    return source;
}

}  // namespace hdhair
