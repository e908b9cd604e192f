#pragma once
// Which strand fragment a pixel's depth and ids belong to.
//
// Opaque frames draw every strand solid, so the depth buffer and the id
// images hold the nearest fragment, as for any opaque geometry. Blended
// frames (binSorted, unsorted, exact) show strands through each other; there
// the depth output and the primId, instanceId and elementId outputs all name
// the nearest strand fragment whose alpha -- coverage x opacity, what the
// fragment adds to the pixel -- is at least kNearestStrandMinAlpha. Fainter
// fragments still colour the pixel but are looked through, for depth and for
// picking alike, so that depth and ids always describe the same fragment.
// Pixels with no such fragment have depth 1 and ids -1.
//
// The value is Storm's default alpha threshold (0.1). The shaders receive it
// through the frame uniforms (FrameUniforms::nearestStrandMinAlpha), so this
// is the only place it is written down.

namespace hdhair {

constexpr float kNearestStrandMinAlpha = 0.1f;

}  // namespace hdhair
