#include "hdHair/plan/TransparencyPlanner.h"

#include <fmt/format.h>

#include "hdHair/plan/FrameFallback.h"
#include "hdHair/plan/FrameRecipe.h"
#include "hdHair/plan/SettingValues.h"

namespace hdhair {

void planTransparency(FrameRecipe& recipe, const SettingValues& settings, const StrandSummary& strands,
                      const FrameFallbacks& fallbacks) {
    const TransparencyPath requested = settings.transparency;
    const double threshold = settings.minPixelWidth;
    const bool needsBlending = !strands.allOpaque || strands.minProjectedWidthPixels < threshold;
    std::string& why = recipe.transparencyReason;
    if (requested == TransparencyPath::Opaque) {
        recipe.transparency = TransparencyPath::Opaque;
        why = "transparency=opaque: opacity and sub-pixel coverage ignored";
    } else if (!needsBlending) {
        recipe.transparency = TransparencyPath::Opaque;
        why = fmt::format("every strand is opaque and at least {:.2f} px wide (>= minPixelWidth {}): no blending "
                          "or sorting needed",
                          strands.minProjectedWidthPixels, threshold);
    } else if (requested == TransparencyPath::Exact && fallbacks.exactListsOverBudget) {
        recipe.transparency = TransparencyPath::BinSorted;
        recipe.sortBins = kFallbackSortBins;
        why = fmt::format("exact fell back: its fragment lists were over exactMemoryMB={}, so {} bins, drawn far to "
                          "near with pre-multiplied blending",
                          settings.exactMemoryMB, recipe.sortBins);
    } else if (requested == TransparencyPath::Exact) {
        recipe.transparency = TransparencyPath::Exact;
        why = "per-pixel fragment lists sorted by depth (exact)";
    } else if (requested == TransparencyPath::Unsorted) {
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
    recipe.exactOverflowFails = settings.exactOverflow == ExactOverflow::Fail;
}

}  // namespace hdhair
