#pragma once
// How a frame's strands are composited: what the transparency setting asks
// for, unless the strands do not need it (every one opaque and at least
// minPixelWidth wide: no blending, no sort).

#include <string>

#include "hdHair/plan/SettingTokens.h"

namespace hdhair {

struct FrameFallbacks;
struct FrameRecipe;
struct SettingValues;
struct StrandSummary;

// Sets the recipe's transparency, sortBins, msaaSamples, transparencyReason
// and exact transparency's budget (exactMemoryMB, exactOverflowFails).
// Exact transparency whose lists an earlier attempt at the frame found over
// exactMemoryMB (fallbacks) is bin sorted with kFallbackSortBins bins.
void planTransparency(FrameRecipe& recipe, const SettingValues& settings, const StrandSummary& strands,
                      const FrameFallbacks& fallbacks);

}  // namespace hdhair
