#pragma once
// Which fragment a pixel's depth and ids belong to.
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
// Meshes (opaque occluders, drawn before the strands with depth written)
// take part as opaque geometry: a strand fragment behind a mesh fails the
// depth test on every path, so a pixel's depth and ids are those of the
// nearer of the nearest mesh fragment and the nearest strand fragment in
// front of it that meets the threshold. On the opaque path that is the depth
// buffer. Under blending the mesh pass writes its depth to the nearest-depth
// image as well (before any strand, so the min blend then keeps a nearer
// qualifying strand's) and its ids; the blended strand pass leaves the ids
// alone, and the ids pass (depth-tested against the meshes) or exact's
// resolve replaces them only where a qualifying strand lies in front. Faint
// hair over a mesh is looked through: the mesh is what a user picks.
//
// The value is Storm's default alpha threshold (0.1). The shaders receive it
// through the frame uniforms (FrameUniforms::nearestStrandMinAlpha), so this
// is the only place it is written down.

namespace hdhair {

constexpr float kNearestStrandMinAlpha = 0.1f;

}  // namespace hdhair
