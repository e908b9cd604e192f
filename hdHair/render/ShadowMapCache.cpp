#include "hdHair/render/ShadowMapCache.h"

#include <algorithm>
#include <set>

#include <fmt/format.h>

namespace hdhair {

ShadowFrame ShadowMapCache::update(const std::vector<ShadowMapRequest>& requests, const ShadowPlan& shadows,
                                   uint64_t castersVersion, bool rebuildTogether) {
    // What shapes the maps, without this frame's lights (each light's view
    // is compared on its own below).
    ShadowPlan shape = shadows;
    shape.lights.clear();
    // Lights that no longer cast give their slots back.
    std::set<std::string> keys;
    for (const ShadowMapRequest& request : requests) keys.insert(request.key);
    for (auto it = held_.begin(); it != held_.end();) it = keys.count(it->first) ? std::next(it) : held_.erase(it);

    // Slots: new lights take the lowest free one; storage grows to the next
    // power of two, which loses what it held.
    std::set<int> used;
    for (const auto& [key, held] : held_) used.insert(held.slot);
    std::vector<int> slots;
    for (const ShadowMapRequest& request : requests) {
        auto it = held_.find(request.key);
        int slot = 0;
        if (it != held_.end()) {
            slot = it->second.slot;
        } else {
            while (used.count(slot)) ++slot;
            used.insert(slot);
        }
        slots.push_back(slot);
    }
    const int needed = used.empty() ? 0 : *used.rbegin() + 1;
    bool grew = false;
    if (needed > capacity_) {
        int capacity = std::max(capacity_, 1);
        while (capacity < needed) capacity *= 2;
        grew = capacity_ > 0 || !held_.empty();
        capacity_ = capacity;
    }

    // Why each map is rebuilt (empty: kept).
    std::vector<std::string> why(requests.size());
    for (size_t i = 0; i < requests.size(); ++i) {
        const ShadowMapRequest& request = requests[i];
        auto it = held_.find(request.key);
        if (it == held_.end()) {
            why[i] = "a new shadow-casting light";
        } else if (grew) {
            why[i] = fmt::format("the map storage grew to {} lights", capacity_);
        } else if (it->second.shape != shape) {
            why[i] = "the shadow or tessellation settings changed";
        } else if (it->second.castersVersion != castersVersion) {
            why[i] = "the hair changed";
        } else if (it->second.view != request.view || it->second.meshView != request.meshView) {
            why[i] = request.followsCamera ? "the camera moved, and the camera light with it" : "the light moved";
        }
    }
    if (rebuildTogether) {
        auto rebuilt = std::find_if(why.begin(), why.end(), [](const std::string& w) { return !w.empty(); });
        if (rebuilt != why.end()) {
            const std::string other = requests[size_t(rebuilt - why.begin())].key;
            for (std::string& reason : why)
                if (reason.empty()) reason = "its fragment lists share one pool with " + other + "'s, which changed";
        }
    }

    ShadowFrame frame;
    frame.capacity = capacity_;
    for (size_t i = 0; i < requests.size(); ++i) {
        ShadowMapDecision decision;
        decision.slot = slots[i];
        decision.rebuild = !why[i].empty();
        decision.reason = decision.rebuild ? "rebuilt: " + why[i]
                                           : "kept: light, hair and settings unchanged since it was built";
        frame.maps.push_back(decision);
        Held& held = held_[requests[i].key];
        held = Held{slots[i], requests[i].view, requests[i].meshView, shape, castersVersion};
    }
    return frame;
}

}  // namespace hdhair
