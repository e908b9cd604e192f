#include "hdHair/base/ComposedPrimBound.h"

#include <fmt/format.h>

#include "hdHair/base/CompositionLimits.h"
#include "hdHair/base/InputError.h"

namespace hdhair {

ComposedPrimBound::ComposedPrimBound(std::string stagePath, Describe describe)
    : stagePath_(std::move(stagePath)), describe_(std::move(describe)) {}

void ComposedPrimBound::check(const std::string& rootStack) { primsBelow(Site{rootStack, "/"}, 0); }

double ComposedPrimBound::primsBelow(const Site& site, int depth) {
    const std::string key = site.stack + "\n" + site.path;
    if (auto known = counts_.find(key); known != counts_.end()) return known->second;
    // A cycle, or nesting past the cap, adds nothing here (and bounds this
    // recursion): composing reports either, as an error naming the arc.
    if (depth > kMaxCompositionNesting || !active_.insert(key).second) return 0.0;
    const Specs specs = describe_(site);
    double total = 0.0;
    for (const Site& arc : specs.arcs) total += primsBelow(arc, depth + 1);
    for (const std::string& name : specs.children)
        total += 1.0 + primsBelow(Site{site.stack, (site.path == "/" ? "/" : site.path + "/") + name}, depth + 1);
    if (total > double(kMaxComposedPrims))
        throw InputError(fmt::format("{}: the stage composes more than {} prims, the most hdHair reads (<{}> alone "
                                     "composes about {:.3g}, counted from its layers before composing)",
                                     stagePath_, kMaxComposedPrims, site.path, total));
    active_.erase(key);
    counts_[key] = total;
    return total;
}

}  // namespace hdhair
