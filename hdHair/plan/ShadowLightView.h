#pragma once
// The view a shadow-casting light sees the hair through: where its deep
// opacity map (or, with shadowMode=reference, its fragment lists) is drawn
// from, fitted to the casters' bounds (Svoboda 2012, section 2.7.1: the
// minimal frustum that holds the hair's bounding box).
//
// - Distant lights: orthographic, looking along the light's direction, a
//   square window around the bounds' projection (texels stay square, so one
//   pixelsPerUnit serves the coverage rule).
// - Sphere, rect and disk lights (spot lights are these with a
//   UsdLuxShapingAPI cone): perspective from the light's position, a square
//   symmetric frustum aimed at the bounds' centre just wide enough for every
//   corner; for a shaped light, aimed along its axis as wide as its cone when
//   that is narrower.
// - Fallback: a local light inside the bounds, touching them, or so close
//   that the frustum would be wider than kMaxShadowHalfFieldOfViewDegrees
//   cannot be held by one perspective view (it would need a cube map); unless
//   its cone is narrow enough to aim along its axis, the view is not valid
//   and `fallback` says why: the renderer warns and shades that light
//   unshadowed. So do a light transform or casters' bounds that are not
//   finite. Never a silently wrong map.
//
// Depth in a light view is linear: the distance along `forward` from `eye`,
// in world units, for orthographic and perspective views alike, so that the
// opacity layers are spaced in world units whatever the projection
// (shaders/include/shadows.glsl shadowLinearDepth).

#include <string>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "hdHair/shading/ShadingLight.h"

namespace hdhair {

// What casts: the drawn strands' world bounds (widths included) and their
// widest width, for margins.
struct CasterBounds {
    glm::dvec3 min{1.0}, max{-1.0};  // min > max: nothing casts
    double maxWidth = 0.0;
    bool empty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
};

// Bounds that hold both (an empty one adds nothing), with the wider width.
CasterBounds unite(const CasterBounds& a, const CasterBounds& b);

// The widest frustum a perspective light view may have (half-angle).
constexpr double kMaxShadowHalfFieldOfViewDegrees = 75.0;

struct ShadowLightView {
    bool valid = false;
    std::string fallback;  // why not valid, for the warning and --explain
    // Not valid because the light is a local one inside or too close to the
    // bounds: it would need a cube map (shadowMode=auto shadows it through
    // the hair's density volume instead, ShadowPlanner.h).
    bool needsCubeMap = false;
    bool orthographic = true;
    glm::dmat4 view{1.0}, projection{1.0};  // world -> light view -> clip (GL conventions)
    glm::dvec3 eye{0.0}, forward{0.0, 0.0, -1.0};
    double nearDepth = 0.0, farDepth = 0.0;  // the casters' linear depth range in this view
    // World size of one texel: orthographic, everywhere; perspective, at
    // linear depth 1 (it grows with depth).
    double texelSize = 0.0;
    int resolution = 0;  // texels across (square maps)
    // Pixels one world unit spans at clip w = 1, horizontally: the coverage
    // rule's scale in this view (FrameUniforms::pixelsPerUnit).
    double pixelsPerUnit = 0.0;
    bool operator==(const ShadowLightView& other) const;
    bool operator!=(const ShadowLightView& other) const { return !(*this == other); }
};

ShadowLightView fitShadowLightView(const ShadingLight& light, const CasterBounds& casters, int resolution);

}  // namespace hdhair
