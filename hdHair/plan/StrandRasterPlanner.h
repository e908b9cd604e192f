#pragma once
// Who rasterises the camera's blended strands: GL's tessellator and
// rasteriser (StrandPass, FragmentListPass's hardware lists), or the compute
// rasteriser (shaders/strandRaster.comp), which cuts, rasterises and shades
// spans in compute workgroups, on every core under llvmpipe, and composites
// them from per-pixel lists (so exactly, whatever transparency asked for).
// It pays for thin strands: its cost grows with the fragments it lists,
// each dearer than a hardware fragment, while the hardware's is dominated
// by the geometry work per span, which llvmpipe does on one thread.

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "hdHair/plan/SettingTokens.h"

namespace hdhair {

struct FrameFallbacks;
struct SettingValues;
struct StrandSummary;
struct TransparencyPlan;

// Who the plan gives the blended strands (the strandRaster setting asks
// for it: StrandRasterSetting).
enum class StrandRaster { Hardware, Compute };
template <>
struct TokenTable<StrandRaster> {
    static constexpr std::array<TokenName<StrandRaster>, 2> names{
        {{StrandRaster::Hardware, "hardware"}, {StrandRaster::Compute, "compute"}}};
};

// Who rasterises the blended strands, and the compute rasteriser's budget.
struct StrandRasterPlan {
    StrandRaster rasteriser = StrandRaster::Hardware;
    std::string reason;  // why, for --explain
    // The compute rasteriser's fragment lists are bounded by
    // strandRasterMemoryMB; a frame over it is planned again for the
    // hardware (FrameFallback.h).
    int memoryMB = 512;
    // With the compute rasteriser, per drawn prim (draw order): whether the
    // hardware rasteriser lists its fragments instead, into the same
    // per-pixel lists (strandRaster=auto's prims too wide for compute).
    // Empty: compute lists every prim.
    std::vector<bool> listedByHardware;
    // About how many fragments the frame's lists will hold (each prim's
    // segments times the pixels StrandSummary estimates a span of it
    // covers), so that a first frame sizes its list storage once rather
    // than render again into storage of the size it counted; 0 when unknown
    // (bounds reaching the camera, or no per-prim figures).
    uint64_t expectedFragments = 0;
    bool mixesRasterisers() const {
        return rasteriser == StrandRaster::Compute &&
               std::find(listedByHardware.begin(), listedByHardware.end(), true) != listedByHardware.end();
    }
};

// Who rasterises the strands, given the transparency path (the opaque path
// is always the hardware's).
// `approximationAskedFor`: the explicit setting (--setting, a Hydra render
// setting; not a default or a preset) that asks for an unsorted or
// bin-sorted frame by a value other than the default, "transparency=unsorted"
// or "sortBins=16", or empty. auto keeps such a frame on the hardware, since
// the compute rasteriser's lists composite exactly and have no bins.
// A frame whose compute lists an earlier attempt found over
// strandRasterMemoryMB (fallbacks) is drawn by the hardware.
StrandRasterPlan planStrandRaster(const TransparencyPlan& transparency, const SettingValues& settings,
                                  const StrandSummary& strands, const std::string& approximationAskedFor,
                                  const FrameFallbacks& fallbacks);

}  // namespace hdhair
