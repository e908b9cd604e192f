#pragma once
// What a frame's images take at once, estimated from its size before any is
// allocated: the GL targets (colour RGBA32F and depth per sample, ids, the
// multisample resolve, the light-batch target) and the CPU images read back
// and written (colour, depth, ids, the display image and the writer's copy).
// On llvmpipe the GL targets are this process's memory too.

#include <cstdint>

#include "hdHair/base/AvailableMemory.h"
#include "hdHair/plan/RenderSettings.h"

namespace hdhair {

uint64_t frameImageBytes(int width, int height, int msaaSamples, bool ids, bool depth);

// Throws std::runtime_error, one line with the sizes and the widest image
// that fits, when the frame's images need more than `available` (what the
// process can take: availableMemory()). `hostBytesPerPixel`: what a host
// holds besides (a Hydra host's render buffers and its copy of the colour).
void checkFrameFitsMemory(int width, int height, const RenderSettings& settings, bool ids, bool depth,
                          uint64_t hostBytesPerPixel, const AvailableMemory& available);

}  // namespace hdhair
