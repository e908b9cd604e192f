#include "hdHair/render/TransparencyPlanner.h"

#include <fmt/format.h>

#include "hdHair/render/FrameRecipe.h"
#include "hdHair/render/SettingValues.h"

namespace hdhair {

const char* toString(TransparencyPath path) {
    switch (path) {
    case TransparencyPath::Opaque: return "opaque";
    case TransparencyPath::BinSorted: return "binSorted";
    case TransparencyPath::Exact: return "exact";
    case TransparencyPath::Unsorted: return "unsorted";
    }
    return "opaque";
}

void planTransparency(FrameRecipe& recipe, const SettingValues& settings, const StrandSummary& strands) {
    const std::string& requested = settings.transparency;
    const double threshold = settings.minPixelWidth;
    const bool needsBlending = !strands.allOpaque || strands.minProjectedWidthPixels < threshold;
    std::string& why = recipe.transparencyReason;
    if (requested == "opaque") {
        recipe.transparency = TransparencyPath::Opaque;
        why = "transparency=opaque: opacity and sub-pixel coverage ignored";
    } else if (!needsBlending) {
        recipe.transparency = TransparencyPath::Opaque;
        why = fmt::format("every strand is opaque and at least {:.2f} px wide (>= minPixelWidth {}): no blending "
                          "or sorting needed",
                          strands.minProjectedWidthPixels, threshold);
    } else if (requested == "exact") {
        recipe.transparency = TransparencyPath::Exact;
        why = "per-pixel fragment lists sorted by depth (exact)";
    } else if (requested == "unsorted") {
        recipe.transparency = TransparencyPath::Unsorted;
        why = "pre-multiplied blending in authored order, unsorted";
    } else {
        recipe.transparency = TransparencyPath::BinSorted;
        recipe.sortBins = uint32_t(settings.sortBins);
        why = fmt::format("{} bins, drawn far to near with pre-multiplied blending", recipe.sortBins);
    }
    if (recipe.transparency != TransparencyPath::Opaque)
        why += fmt::format(" ({}; thinnest strand {:.2f} px)", strands.allOpaque ? "opaque strands" : "translucent strands",
                           strands.minProjectedWidthPixels);
    if (recipe.transparency == TransparencyPath::Opaque) recipe.msaaSamples = settings.msaaSamples;
    recipe.exactMemoryMB = settings.exactMemoryMB;
    recipe.exactOverflowFails = settings.exactOverflow == "fail";
}

}  // namespace hdhair
