#include "hdHair/render/StrandRasterPlanner.h"

#include <cmath>

#include <fmt/format.h>

#include "hdHair/render/FrameRecipe.h"
#include "hdHair/render/SettingValues.h"

namespace hdhair {

const char* toString(StrandRaster raster) { return raster == StrandRaster::Compute ? "compute" : "hardware"; }

void planStrandRaster(FrameRecipe& recipe, const SettingValues& settings, const StrandSummary& strands,
                      const std::string& approximationAskedFor) {
    const std::string& requested = settings.strandRaster;
    const double widest = strands.maxProjectedWidthPixels;
    const double threshold = settings.strandRasterMaxPixelWidth;
    std::string& why = recipe.strandRasterReason;
    recipe.strandRaster = StrandRaster::Hardware;
    recipe.strandRasterMemoryMB = settings.strandRasterMemoryMB;
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
    } else if (!std::isfinite(widest)) {
        why = "hardware: the strands' bounds reach the camera, so no width bounds them (strandRaster=auto)";
    } else if (widest > threshold) {
        why = fmt::format("hardware: the widest strand may project {:.2f} px, over strandRasterMaxPixelWidth {} "
                          "(strandRaster=auto)",
                          widest, threshold);
    } else {
        recipe.strandRaster = StrandRaster::Compute;
        why = fmt::format("compute: every strand projects at most {:.2f} px wide (strandRasterMaxPixelWidth {}; "
                          "strandRaster=auto)",
                          widest, threshold);
    }
    if (recipe.strandRaster == StrandRaster::Compute)
        why += ", spans cut, rasterised and shaded in compute, composited from per-pixel lists sorted by depth";
}

}  // namespace hdhair
