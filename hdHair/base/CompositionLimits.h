#pragma once
// Caps that keep hostile stages (a reference chain that doubles at each
// layer, "billion laughs"; thousands of layers) from exhausting memory or the
// stack, each far beyond what real stages use. Both readers apply them: the
// embedded reader as it composes, the OpenUSD path by bounding the stage
// from its layers before OpenUSD composes it (docs/hard-cases.md).

#include <cstddef>

namespace hdhair {

constexpr size_t kMaxLayers = 10000;           // layers one stage loads
constexpr size_t kMaxComposedPrims = 5000000;  // prims one stage composes

}  // namespace hdhair
