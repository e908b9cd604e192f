#pragma once
// Who rasterises the camera's blended strands: GL's tessellator and
// rasteriser (StrandPass, FragmentListPass's hardware lists), or the compute
// rasteriser (shaders/strandRaster.comp), which cuts, rasterises and shades
// spans in compute workgroups, on every core under llvmpipe, and composites
// them from per-pixel lists (so exactly, whatever transparency asked for).
// It pays for thin strands: its cost per segment grows with the pixels its
// bounding box covers, where the hardware's grows with the pixels covered.

#include <string>

namespace hdhair {

struct FrameRecipe;
struct SettingValues;
struct StrandSummary;

enum class StrandRaster { Hardware, Compute };
const char* toString(StrandRaster raster);

// Sets the recipe's strandRaster, strandRasterReason and
// strandRasterMemoryMB; after planTransparency, whose path it reads.
void planStrandRaster(FrameRecipe& recipe, const SettingValues& settings, const StrandSummary& strands);

}  // namespace hdhair
