#pragma once
// Where a latlong (equirectangular) dome texture puts each direction: the
// convention of Storm in OpenUSD 24.08, so that a stage lit by a textured
// DomeLight is lit from the same side in hdHair as in usdview's Storm.
//
// Texture coordinates: u runs left to right across the image, v top to
// bottom (v = 0 is the file's first row, as OpenImageIO reads it). In the
// dome's own frame a unit direction d = (x, y, z) sits at
//   u = 1/2 − atan2(x, z) / (2π)   (wrapped into [0, 1)),   v = acos(y) / π,
// and back: longitude φ = π(1 − 2u), polar angle θ = πv,
//   d = (sin θ sin φ, cos θ, sin θ cos φ).
// So +Y is the top row, −Y the bottom row; on the horizon, the image's
// centre (u = 1/2) is +Z, u = 1/4 is +X, u = 3/4 is −X and both edges −Z.
//
// Where this comes from (OpenUSD v24.08):
// - pxr/usd/usdLux/schema.usda, DomeLight: "the dome's default orientation
//   is such that its top pole is aligned with the world's +Y axis", with the
//   OpenEXR latlong convention: pixel (min.x, min.y) has latitude +π/2 and
//   longitude +π, pixel (max.x, max.y) latitude −π/2 and longitude −π;
//   latitude 0, longitude 0 is +z; latitude 0, longitude π/2 is +x.
// - Storm agrees: pxr/imaging/glf/shaders/simpleLighting.glslfx
//   projectSphericalToLatLong looks the prefiltered dome maps up at
//   ((atan(z, x) + π/2) / 2π, acos(y) / π); those maps were written by
//   pxr/imaging/hdSt/shaders/domeLight.glslfx, whose GetWorldPos gives texel
//   (s, t) the direction (cos α sin β, cos β, sin α sin β), α = 2πs − π,
//   β = πt, and whose SampleEnvMapLod reads the source texture at
//   ((atan(z, x) + π) / 2π, acos(y) / π). Composed, the source texture is
//   read at u = (atan2(z, x) + π/2) / 2π, which is the u above. The source
//   is loaded with flipVertically = true (hdSt/simpleLightingShader.cpp),
//   which hdSt/textureObject.cpp turns into HioImage::OriginUpperLeft: the
//   file's top row is t = 0, so +Y is the top of the image.
//
// The dome's transform: Storm looks a world direction ω up at the dome-frame
// direction d = normalize(M⁻¹ ω), M the light's world transform
// (worldToLightTransform = the inverse of the light's transform,
// glf/simpleLightingContext.cpp). Turning the dome by a rotation R therefore
// turns its lighting by R: the texel seen along d in the dome's frame now
// lights from R d. domeLightDirectionToWorld() applies this.

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace hdhair {

// The unit direction, in the dome's frame, at texture coordinates (u, v).
glm::vec3 latlongDirection(float u, float v);

// The texture coordinates of a direction in the dome's frame (need not be
// unit length; not zero): u in [0, 1), v in [0, 1].
glm::vec2 latlongCoordinates(const glm::vec3& direction);

// A dome-frame direction in world space: normalize(M d), M the dome's world
// transform (its translation does not matter).
glm::vec3 domeLightDirectionToWorld(const glm::dmat4& domeToWorld, const glm::vec3& domeDirection);

// A world direction in the dome's frame: normalize(M⁻¹ ω), the direction
// Storm looks the texture up at.
glm::vec3 worldDirectionToDomeLight(const glm::dmat4& domeToWorld, const glm::vec3& worldDirection);

}  // namespace hdhair
