#pragma once
// An upper bound on the prims a stage composes, from its layers alone,
// before anything is composed: each prim spec of a layer stack counts once,
// and each arc (a reference, payload, inherit or specialize; every variant)
// adds the prims below its target as often as it is used. A chain of layers
// that each reference the next twice ("billion laughs") doubles the bound
// at every layer, so it is refused in milliseconds where composing it would
// take minutes and gigabytes. Memoised by site, so the count itself is
// linear in the specs. Both readers describe their layers to it (the
// embedded reader's StageComposer, the OpenUSD path's UsdStageChecks).

#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace hdhair {

class ComposedPrimBound {
public:
    // A site: a layer stack (named by its root layer's identifier) and a
    // prim path in it ("/" for the pseudo-root).
    struct Site {
        std::string stack;
        std::string path;
    };
    // What a site's specs hold: its children's names (across the stack) and
    // the sites its arcs bring in (each once per use).
    struct Specs {
        std::vector<std::string> children;
        std::vector<Site> arcs;
    };
    using Describe = std::function<Specs(const Site& site)>;

    // `stagePath` starts the errors.
    ComposedPrimBound(std::string stagePath, Describe describe);

    // Throws InputError when the stage composes more than kMaxComposedPrims
    // prims. Sites nested past kMaxCompositionNesting are not counted (the
    // composer refuses such nesting itself).
    void check(const std::string& rootStack);

private:
    double primsBelow(const Site& site, int depth);

    std::string stagePath_;
    Describe describe_;
    std::map<std::string, double> counts_;
    std::set<std::string> active_;
};

// Namespace and arc nesting the bound follows (the embedded reader's cap).
constexpr int kMaxCompositionNesting = 1000;

}  // namespace hdhair
