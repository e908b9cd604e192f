#pragma once
// How a frame's strands are composited: what the transparency setting asks
// for, unless the strands do not need it (every one opaque and at least
// minPixelWidth wide: no blending, no sort).

#include <cstdint>
#include <string>

#include "hdHair/plan/SettingTokens.h"

namespace hdhair {

struct FrameFallbacks;
struct SettingValues;
struct StrandSummary;

// How the strands are composited.
struct TransparencyPlan {
    TransparencyPath path = TransparencyPath::Opaque;
    std::string reason;     // why this path, for --explain
    uint32_t sortBins = 0;  // for BinSorted
    int msaaSamples = 0;    // for Opaque
    // Exact transparency's fragment budget (exactMemoryMB), and whether a
    // frame over it fails (exactOverflow=fail) rather than fall back.
    int exactMemoryMB = 512;
    bool exactOverflowFails = false;
};

// The transparency path the settings ask for, unless the strands do not
// need it. Exact transparency whose lists an earlier attempt at the frame
// found over exactMemoryMB (fallbacks) is bin sorted with kFallbackSortBins
// bins.
TransparencyPlan planTransparency(const SettingValues& settings, const StrandSummary& strands,
                                  const FrameFallbacks& fallbacks);

}  // namespace hdhair
