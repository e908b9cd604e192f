#include "hdHair/plan/StrandRasterPlanner.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "hdHair/plan/FrameFallback.h"
#include "hdHair/plan/SceneSummary.h"
#include "hdHair/plan/SettingValues.h"
#include "hdHair/plan/TransparencyPlanner.h"

namespace hdhair {

namespace {

// What strandRaster=auto weighs a prim by.
struct AutoRule {
    double maxPixelWidth = 0.0;        // strandRasterMaxPixelWidth
    double maxFragmentsPerSpan = 0.0;  // strandRasterMaxFragmentsPerSpan
};

// strandRaster=auto: compute for the prims whose strands project at most
// rule.maxPixelWidth px wide and whose spans cover about
// rule.maxFragmentsPerSpan pixels or fewer: the compute rasteriser's cost
// grows with the fragments it lists, the hardware's mostly with the spans
// (docs/performance.md, "Where compute pays"). Other prims are listed by
// the hardware rasteriser into the same per-pixel lists, one resolve
// compositing both, when the prims within the rule hold at least half the
// frame's segments. Otherwise the frame keeps the hardware.
void planByPrim(StrandRasterPlan& plan, const StrandSummary& strands, const AutoRule& rule) {
    std::string& why = plan.reason;
    // Summaries made without per-prim figures count as one prim.
    std::vector<StrandSummary::PrimRaster> prims = strands.prims;
    if (prims.empty()) prims.push_back({strands.maxProjectedWidthPixels, strands.segments, 0.0});
    auto withinRule = [&rule](const StrandSummary::PrimRaster& prim) {
        return std::isfinite(prim.maxProjectedWidthPixels) && prim.maxProjectedWidthPixels <= rule.maxPixelWidth &&
               prim.fragmentsPerSpan <= rule.maxFragmentsPerSpan;
    };
    uint64_t thinSegments = 0, otherSegments = 0;
    size_t others = 0;
    double widestThin = 0.0, widestOther = 0.0, coveredThin = 0.0, coveredOther = 0.0;
    for (const StrandSummary::PrimRaster& prim : prims) {
        if (withinRule(prim)) {
            thinSegments += prim.segments;
            widestThin = std::max(widestThin, prim.maxProjectedWidthPixels);
            coveredThin = std::max(coveredThin, prim.fragmentsPerSpan);
        } else {
            otherSegments += prim.segments;
            widestOther = std::max(widestOther, prim.maxProjectedWidthPixels);
            coveredOther = std::max(coveredOther, prim.fragmentsPerSpan);
            ++others;
        }
    }
    const std::string ruleText = fmt::format("strandRasterMaxPixelWidth {}, strandRasterMaxFragmentsPerSpan {}; "
                                             "strandRaster=auto",
                                             rule.maxPixelWidth, rule.maxFragmentsPerSpan);
    const std::string thinAs =
        fmt::format("project at most {:.2f} px wide and cover about {:.1f} px a span or fewer", widestThin, coveredThin);
    // What puts the other prims outside the rule, the first that does.
    const std::string otherAs = !std::isfinite(widestOther) ? std::string("reach the camera's plane, so no width "
                                                                          "bounds them")
                                : widestOther > rule.maxPixelWidth
                                    ? fmt::format("may project {:.2f} px wide", widestOther)
                                    : fmt::format("cover about {:.1f} px a span", coveredOther);
    if (others == 0) {
        plan.rasteriser = StrandRaster::Compute;
        why = fmt::format("compute: the strands {} ({})", thinAs, ruleText);
    } else if (thinSegments > 0 && thinSegments >= otherSegments) {
        plan.rasteriser = StrandRaster::Compute;
        plan.listedByHardware.clear();
        for (const StrandSummary::PrimRaster& prim : prims) plan.listedByHardware.push_back(!withinRule(prim));
        why = fmt::format("compute for {} of {} prims ({} of {} segments), whose strands {}; the hardware rasteriser "
                          "lists the {} other prim(s), whose strands {}, into the same lists ({})",
                          prims.size() - others, prims.size(), thinSegments, thinSegments + otherSegments, thinAs,
                          others, otherAs, ruleText);
    } else {
        why = fmt::format("hardware: the strands {}{} ({})", otherAs,
                          thinSegments > 0 ? "; the prims within the rule hold under half the segments" : "",
                          ruleText);
    }
}

// Each prim's segments times the pixels a span of it covers, summed; 0 when
// a prim's estimate is unknown or unbounded.
uint64_t expectedFragments(const StrandSummary& strands) {
    double fragments = 0.0;
    for (const StrandSummary::PrimRaster& prim : strands.prims) {
        if (!std::isfinite(prim.fragmentsPerSpan) || prim.fragmentsPerSpan <= 0.0) return 0;
        fragments += double(prim.segments) * prim.fragmentsPerSpan;
    }
    return fragments < 1e15 ? uint64_t(fragments) : 0;
}

}  // namespace

StrandRasterPlan planStrandRaster(const TransparencyPlan& transparency, const SettingValues& settings,
                                  const StrandSummary& strands, const std::string& approximationAskedFor,
                                  const FrameFallbacks& fallbacks) {
    StrandRasterPlan plan;
    const StrandRasterSetting requested = settings.strandRaster;
    std::string& why = plan.reason;
    plan.memoryMB = settings.strandRasterMemoryMB;
    if (transparency.path == TransparencyPath::Opaque) {
        why = "hardware: the opaque path draws depth-tested ribbons, with nothing to composite";
    } else if (fallbacks.computeListsOverBudget) {
        why = fmt::format("hardware: the compute rasteriser's lists were over strandRasterMemoryMB={}",
                          settings.strandRasterMemoryMB);
    } else if (fallbacks.exactListsOverBudget) {
        // Exact lists are only listed by the hardware: the frame whose
        // lists overflowed was on it, and its bin sort stays there.
        why = "hardware: exact transparency's lists were over exactMemoryMB, and the bin sort that replaces them "
              "is drawn by the hardware rasteriser";
    } else if (requested == StrandRasterSetting::Hardware) {
        why = "hardware: strandRaster=hardware";
    } else if (requested == StrandRasterSetting::Compute) {
        plan.rasteriser = StrandRaster::Compute;
        why = "compute: strandRaster=compute";
    } else if (!approximationAskedFor.empty() && transparency.path != TransparencyPath::Exact) {
        why = fmt::format("hardware: {} is set, and the compute rasteriser composites exactly, without bins "
                          "(strandRaster=auto)",
                          approximationAskedFor);
    } else {
        planByPrim(plan, strands, {settings.strandRasterMaxPixelWidth, settings.strandRasterMaxFragmentsPerSpan});
    }
    if (plan.rasteriser == StrandRaster::Compute)
        why += ", spans cut, rasterised and shaded in compute, composited from per-pixel lists sorted by depth";
    plan.expectedFragments = expectedFragments(strands);
    return plan;
}

}  // namespace hdhair
