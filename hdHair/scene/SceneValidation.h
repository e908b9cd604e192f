#pragma once
// Checks of the values a light, a camera or a prim's transform brings in,
// shared by every front end (the embedded .usda reader, the Hydra plugin) so
// that both accept, repair and refuse alike. Primvars and topology have their
// own checks where they are resolved (hdHair/curves, hdHair/meshes); these
// cover the inputs that reach shading and the camera as plain numbers, where
// a NaN or an absurd value would otherwise end in NaN/Inf pixels or a blank
// frame without a word.
//
// Lights (repairLight), each repair a warning "<path>.<attribute>: ...":
// - a world transform with a NaN or infinite element, or one that scales the
//   light's emission axis to nothing: the light is skipped;
// - intensity, exposure, color, colorTemperature, angle, radius, width,
//   height, shaping:cone:angle, shaping:cone:softness not finite: USD's
//   fallback, as if unauthored (intensity 50000 for a distant light, else 1;
//   exposure 0; color (1, 1, 1); 6500 K; 0.53; 0.5; 1; 1; 90; 0);
// - out of range: a negative intensity or color component is 0 (negative
//   emission would subtract light and make negative pixels); a negative or
//   zero colorTemperature, and a negative angle, radius, width or height are
//   USD's fallback; a negative cone angle is 0 and a cone softness outside
//   [0, 1] is clamped into it (as shading does, now with a word);
// - a light whose radiance times its area (intensity · 2^exposure · color ·
//   area) is beyond float range after those repairs: skipped.
// Cameras (checkedCamera): a focal length or aperture that is zero, negative
// or not finite, an aperture offset or world transform that is not finite,
// cannot be repaired (there is no right guess for a lens): InputError
// "<file or path>: <path>.<attribute>: ...". A clipping range that is not
// finite, with near <= 0 or far <= near, is replaced by USD's fallback
// [1, 1000000] with a warning. Apertures whose ratio is beyond
// kMostApertureRatio either way are used, with a warning giving the shape.

#include <string>

#include <glm/mat4x4.hpp>

#include "hdHair/scene/CameraPrim.h"
#include "hdHair/scene/LightPrim.h"

namespace hdhair {

class Diagnostics;

// True when every element of the matrix is finite.
bool isFiniteTransform(const glm::dmat4& matrix);

// The warning text for a prim whose world transform is not finite ("" when
// it is): a NaN or infinite xformOp value, or a singular matrix under
// "!invert!" (its inverse divides by a zero determinant).
std::string transformProblem(const std::string& primPath, const glm::dmat4& worldTransform);

// Repairs `light` in place as the table above says, warning at `where` (a
// "file:line:column" or the prim path). Returns false when the light must be
// skipped (its warning already given).
bool repairLight(LightPrim& light, const std::string& where, Diagnostics& diagnostics);

// The widest (and, inverted, the tallest) image shape a camera's apertures
// make without a warning: 100:1, far past any film or sensor format.
constexpr double kMostApertureRatio = 100.0;

// `camera` with its clipping range repaired (warning at `where`); throws
// InputError starting with `where` for what cannot be repaired.
CameraPrim checkedCamera(const CameraPrim& camera, const std::string& where, Diagnostics& diagnostics);

}  // namespace hdhair
