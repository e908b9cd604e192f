#pragma once
// Light edits the benchmarks make so that every timed frame costs what a
// frame after a light moved costs: its shadow maps rebuilt, not kept from
// the frame before (ShadowMapCache.h keeps maps whose light did not move).

#include "hdHair/scene/Scene.h"

namespace hdhair {

// Turns every light of the scene by `radians` about the world's Y axis. A
// microradian changes each light's view, so its map is rebuilt, and the
// image by far less than an 8-bit step.
void turnLightsAboutY(Scene& scene, double radians);

}  // namespace hdhair
