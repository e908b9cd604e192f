#include "hdHair/render/StrandRasterPlanner.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "hdHair/render/FrameRecipe.h"
#include "hdHair/render/SettingValues.h"

namespace hdhair {

namespace {

// strandRaster=auto: compute for the prims whose strands project at most
// `threshold` px wide. Prims wider than it are listed by the hardware
// rasteriser into the same per-pixel lists, one resolve compositing both,
// when the thin prims hold at least half the frame's segments: the compute
// rasteriser pays per thin span, while a wide prim's fragments cost more
// in compute than the hardware's. Otherwise the frame keeps the hardware.
void planByPrim(FrameRecipe& recipe, const StrandSummary& strands, double threshold) {
    std::string& why = recipe.strandRasterReason;
    // Summaries made without per-prim figures count as one prim.
    std::vector<StrandSummary::PrimRaster> prims = strands.prims;
    if (prims.empty()) prims.push_back({strands.maxProjectedWidthPixels, strands.segments});
    auto thin = [threshold](const StrandSummary::PrimRaster& prim) {
        return std::isfinite(prim.maxProjectedWidthPixels) && prim.maxProjectedWidthPixels <= threshold;
    };
    uint64_t thinSegments = 0, wideSegments = 0;
    size_t wideCount = 0;
    double widestThin = 0.0, widestWide = 0.0;
    for (const StrandSummary::PrimRaster& prim : prims) {
        if (thin(prim)) {
            thinSegments += prim.segments;
            widestThin = std::max(widestThin, prim.maxProjectedWidthPixels);
        } else {
            wideSegments += prim.segments;
            widestWide = std::max(widestWide, prim.maxProjectedWidthPixels);
            ++wideCount;
        }
    }
    const std::string rule = fmt::format("strandRasterMaxPixelWidth {}; strandRaster=auto", threshold);
    const std::string wideAs = std::isfinite(widestWide)
                                   ? fmt::format("may project {:.2f} px", widestWide)
                                   : std::string("reach the camera's plane, so no width bounds them");
    if (wideCount == 0) {
        recipe.strandRaster = StrandRaster::Compute;
        why = fmt::format("compute: every strand projects at most {:.2f} px wide ({})", widestThin, rule);
    } else if (thinSegments > 0 && thinSegments >= wideSegments) {
        recipe.strandRaster = StrandRaster::Compute;
        recipe.listedByHardware.clear();
        for (const StrandSummary::PrimRaster& prim : prims) recipe.listedByHardware.push_back(!thin(prim));
        why = fmt::format("compute for {} of {} prims ({} of {} segments), whose strands project at most {:.2f} px "
                          "wide; the hardware rasteriser lists the {} wider prim(s), whose strands {}, into the "
                          "same lists ({})",
                          prims.size() - wideCount, prims.size(), thinSegments, thinSegments + wideSegments,
                          widestThin, wideCount, wideAs, rule);
    } else if (!std::isfinite(widestWide)) {
        why = fmt::format("hardware: the strands' bounds reach the camera, so no width bounds them{} ({})",
                          thinSegments > 0 ? "; the prims within the width hold under half the segments" : "",
                          rule);
    } else {
        why = fmt::format("hardware: the widest strand may project {:.2f} px, over strandRasterMaxPixelWidth {}{} "
                          "(strandRaster=auto)",
                          widestWide, threshold,
                          thinSegments > 0 ? "; the prims within it hold under half the segments" : "");
    }
}

}  // namespace

const char* toString(StrandRaster raster) { return raster == StrandRaster::Compute ? "compute" : "hardware"; }

void planStrandRaster(FrameRecipe& recipe, const SettingValues& settings, const StrandSummary& strands,
                      const std::string& approximationAskedFor) {
    const std::string& requested = settings.strandRaster;
    const double threshold = settings.strandRasterMaxPixelWidth;
    std::string& why = recipe.strandRasterReason;
    recipe.strandRaster = StrandRaster::Hardware;
    recipe.strandRasterMemoryMB = settings.strandRasterMemoryMB;
    recipe.listedByHardware.clear();
    if (recipe.transparency == TransparencyPath::Opaque) {
        why = "hardware: the opaque path draws depth-tested ribbons, with nothing to composite";
    } else if (requested == "hardware") {
        why = "hardware: strandRaster=hardware";
    } else if (requested == "compute") {
        recipe.strandRaster = StrandRaster::Compute;
        why = "compute: strandRaster=compute";
    } else if (!approximationAskedFor.empty() && recipe.transparency != TransparencyPath::Exact) {
        why = fmt::format("hardware: {} is set, and the compute rasteriser composites exactly, without bins "
                          "(strandRaster=auto)",
                          approximationAskedFor);
    } else {
        planByPrim(recipe, strands, threshold);
    }
    if (recipe.strandRaster == StrandRaster::Compute)
        why += ", spans cut, rasterised and shaded in compute, composited from per-pixel lists sorted by depth";
}

}  // namespace hdhair
