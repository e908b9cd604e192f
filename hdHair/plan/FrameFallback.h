#pragma once
// What a pass found that the plan could not know before the frame ran, and
// that makes the frame impossible as planned: the compute rasteriser's or
// exact transparency's fragment lists over their memory, or a reference
// shadow map over GL's storage block. The pass reports it (FrameContext) and
// stops the frame; the Renderer then makes a new plan that avoids it and
// runs that one. No pass edits the plan or runs another pass, and --explain
// and --stats show every plan a frame made and why the next one was made.

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace hdhair {

struct FrameFallback {
    enum class Kind {
        ComputeListsOverBudget,  // strandRasterMemoryMB: the hardware rasteriser draws the strands
        ExactListsOverBudget,    // exactMemoryMB: binSorted with kFallbackSortBins bins
        ShadowMapUnbuildable,    // shadowMode=reference: the light shades unshadowed
    };
    Kind kind = Kind::ComputeListsOverBudget;
    std::string reason;     // "compute -> hardware rasteriser: fragment lists over strandRasterMemoryMB"
    std::string shadowKey;  // ShadowMapUnbuildable: the light ("camera light" or its path)
};

// Exact transparency over its memory falls back to the finest bin sort.
constexpr unsigned kFallbackSortBins = 1024;

// Everything earlier attempts at a frame reported: what its next plan avoids.
struct FrameFallbacks {
    bool computeListsOverBudget = false;
    bool exactListsOverBudget = false;
    // Lights whose maps cannot be built, with why: they get no map.
    std::map<std::string, std::string> unbuildableShadows;
    std::vector<FrameFallback> reported;  // in the order they came

    // Adds one; false when the plans had already avoided it (a pass that
    // reports what the plan avoided is a wiring mistake, never bad input).
    bool add(const FrameFallback& fallback) {
        bool* seen = fallback.kind == FrameFallback::Kind::ComputeListsOverBudget ? &computeListsOverBudget
                     : fallback.kind == FrameFallback::Kind::ExactListsOverBudget ? &exactListsOverBudget
                                                                                  : nullptr;
        if (seen) {
            if (*seen) return false;
            *seen = true;
        } else if (!unbuildableShadows.emplace(fallback.shadowKey, fallback.reason).second) {
            return false;
        }
        reported.push_back(fallback);
        return true;
    }
    bool empty() const { return reported.empty(); }
    // The reasons, joined, for --stats' "fallback".
    std::string describe() const {
        std::string text;
        for (const FrameFallback& fallback : reported) text += (text.empty() ? "" : "; ") + fallback.reason;
        return text;
    }
};

}  // namespace hdhair
