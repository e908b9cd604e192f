#pragma once
// Who rasterises the camera's blended strands: GL's tessellator and
// rasteriser (StrandPass, FragmentListPass's hardware lists), or the compute
// rasteriser (shaders/strandRaster.comp), which cuts, rasterises and shades
// spans in compute workgroups, on every core under llvmpipe, and composites
// them from per-pixel lists (so exactly, whatever transparency asked for).
// It pays for thin strands: its cost grows with the fragments it lists,
// each dearer than a hardware fragment, while the hardware's is dominated
// by the geometry work per span, which llvmpipe does on one thread.

#include <string>

#include "hdHair/plan/SettingTokens.h"

namespace hdhair {

struct FrameFallbacks;
struct FrameRecipe;
struct SettingValues;
struct StrandSummary;

// Who the plan gives the blended strands (the strandRaster setting asks
// for it: StrandRasterSetting).
enum class StrandRaster { Hardware, Compute };
template <>
struct TokenTable<StrandRaster> {
    static constexpr std::array<TokenName<StrandRaster>, 2> names{
        {{StrandRaster::Hardware, "hardware"}, {StrandRaster::Compute, "compute"}}};
};

// Sets the recipe's strandRaster, strandRasterReason, strandRasterMemoryMB
// and listedByHardware (auto: per prim, by strands.prims); after
// planTransparency, whose path it reads.
// `approximationAskedFor`: the explicit setting (--setting, a Hydra render
// setting; not a default or a preset) that asks for an unsorted or
// bin-sorted frame by a value other than the default, "transparency=unsorted"
// or "sortBins=16", or empty. auto keeps such a frame on the hardware, since
// the compute rasteriser's lists composite exactly and have no bins.
// A frame whose compute lists an earlier attempt found over
// strandRasterMemoryMB (fallbacks) is drawn by the hardware.
void planStrandRaster(FrameRecipe& recipe, const SettingValues& settings, const StrandSummary& strands,
                      const std::string& approximationAskedFor, const FrameFallbacks& fallbacks);

}  // namespace hdhair
