#include "hdHair/curves/StrandColorSource.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/curves/PreparedCurves.h"
#include "hdHair/curves/PrimvarResolution.h"
#include "hdHair/scene/CurvesPrim.h"
#include "hdHair/scene/MaterialPrim.h"

namespace hdhair {

namespace {

// A material input over the prim's own channel. `size` is the tuple size the
// channel needs (3 for colour, 1 for opacity).
bool allFinite(const std::vector<float>& values) {
    return std::all_of(values.begin(), values.end(), [](float value) { return std::isfinite(value); });
}

std::string describe(const std::vector<float>& values) {
    return values.size() == 1 ? fmt::format("{}", values[0]) : fmt::format("({})", fmt::join(values, ", "));
}

// `defaultValue`: UsdPreviewSurface's default for the input, which replaces
// an authored value that is not finite (a NaN colour would poison every
// pixel of the strand and everything blended with it).
void applyInput(const MaterialPrim& material, const MaterialInput& input, const std::vector<float>& defaultValue,
                const char* inputName, size_t size, StrandColorSource::Channel& channel, Diagnostics& diagnostics) {
    const std::string where = material.path + ".inputs:" + inputName;
    switch (input.source) {
    case MaterialInput::Source::Value:
        if (input.value.size() != size) {
            diagnostics.warn(where, fmt::format("expected {} value{}, found {}; using the prim's {}", size,
                                                size == 1 ? "" : "s", input.value.size(), channel.primvar));
            return;
        }
        if (!allFinite(input.value)) {
            diagnostics.warn(where, fmt::format("{} is not finite; using UsdPreviewSurface's default {}",
                                                describe(input.value), describe(defaultValue)));
            channel.constant = defaultValue;
            return;
        }
        channel.constant = input.value;
        return;
    case MaterialInput::Source::Primvar:
        channel.primvar = input.primvar;
        // Storm's primvar readers give their fallback for a missing primvar.
        if (input.value.size() == size) {
            if (allFinite(input.value)) {
                channel.fallback = input.value;
            } else {
                diagnostics.warn(where, fmt::format("the primvar reader's fallback {} is not finite; using the "
                                                    "prim's own fallback {}",
                                                    describe(input.value), describe(channel.fallback)));
            }
        }
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
    const MaterialPrim defaults;  // UsdPreviewSurface's defaults
    applyInput(*material, material->diffuseColor, defaults.diffuseColor.value, "diffuseColor", 3, source.color,
               diagnostics);
    applyInput(*material, material->opacity, defaults.opacity.value, "opacity", 1, source.opacity, diagnostics);
    return source;
}

}  // namespace hdhair
