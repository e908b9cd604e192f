#include "hdHair/plan/TransparencyPlanner.h"

#include <fmt/format.h>

#include "hdHair/plan/FrameFallback.h"
#include "hdHair/plan/SceneSummary.h"
#include "hdHair/plan/SettingValues.h"

namespace hdhair {

TransparencyPlan planTransparency(const SettingValues& settings, const StrandSummary& strands,
                                  const FrameFallbacks& fallbacks) {
    TransparencyPlan plan;
    const TransparencyPath requested = settings.transparency;
    const double threshold = settings.minPixelWidth;
    const bool needsBlending = !strands.allOpaque || strands.minProjectedWidthPixels < threshold;
    std::string& why = plan.reason;
    if (requested == TransparencyPath::Opaque) {
        plan.path = TransparencyPath::Opaque;
        why = "transparency=opaque: opacity and sub-pixel coverage ignored";
    } else if (!needsBlending) {
        plan.path = TransparencyPath::Opaque;
        why = fmt::format("every strand is opaque and at least {:.2f} px wide (>= minPixelWidth {}): no blending "
                          "or sorting needed",
                          strands.minProjectedWidthPixels, threshold);
    } else if (requested == TransparencyPath::Exact && fallbacks.exactListsOverBudget) {
        plan.path = TransparencyPath::BinSorted;
        plan.sortBins = kFallbackSortBins;
        why = fmt::format(
            "exact fell back: its fragment lists were over exactMemoryMB={}, so {} bins, drawn far to "
            "near with pre-multiplied blending",
            settings.exactMemoryMB, plan.sortBins);
    } else if (requested == TransparencyPath::Exact) {
        plan.path = TransparencyPath::Exact;
        why = "per-pixel fragment lists sorted by depth (exact)";
    } else if (requested == TransparencyPath::Unsorted) {
        plan.path = TransparencyPath::Unsorted;
        why = "pre-multiplied blending in authored order, unsorted";
    } else {
        plan.path = TransparencyPath::BinSorted;
        plan.sortBins = uint32_t(settings.sortBins);
        why = fmt::format("{} bins, drawn far to near with pre-multiplied blending", plan.sortBins);
    }
    if (plan.path != TransparencyPath::Opaque)
        why += fmt::format(" ({}; thinnest strand {:.2f} px)", strands.allOpaque ? "opaque strands" : "translucent strands",
                           strands.minProjectedWidthPixels);
    if (plan.path == TransparencyPath::Opaque) plan.msaaSamples = settings.msaaSamples;
    plan.exactMemoryMB = settings.exactMemoryMB;
    plan.exactOverflowFails = settings.exactOverflow == ExactOverflow::Fail;
    return plan;
}

}  // namespace hdhair
