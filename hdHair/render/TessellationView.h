#pragma once
// The view whose projected lengths choose how finely every span is cut, in
// the camera pass and in every light's shadow passes alike: a shadow map
// must hold the curve the camera draws, or a strand's own light-view depth
// misses it and self-shadowing does not line up. Culling stays per view
// (strands outside the camera still cast).
//
// The levels are the camera's (shaders/strand.tesc: screenError's or
// projectedLength's rule, at most maxSegmentsPerSpan), taken from the camera
// as it was when the shadow maps were built, and kept while the current
// camera projects the casters alike: at the corners and centre of their
// bounds, a world unit spans within kTessellationScaleTolerance times the
// pixels it spanned, and the view direction has turned by at most
// kTessellationTurnToleranceDegrees. A camera that leaves that tolerance
// re-bases the view, and every shadow map is rebuilt; in between the maps
// are kept, at the price of levels up to 25 % off what the current camera
// would choose. A frame that rebuilds every map anyway (the hair changed,
// the first frame, no map kept) re-bases to the current camera for free.

#include <cstdint>
#include <optional>
#include <string>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace hdhair {

struct CameraView;
struct CasterBounds;

constexpr double kTessellationScaleTolerance = 1.25;
constexpr double kTessellationTurnToleranceDegrees = 10.0;

struct TessellationView {
    glm::dmat4 viewProjection{1.0};
    glm::dvec2 viewport{1.0};
    double pixelsPerUnit = 1.0;  // at clip w = 1
    bool orthographic = false;
    glm::dvec3 eye{0.0}, forward{0.0, 0.0, -1.0};
    uint64_t id = 0;  // a new id each time the view is re-based
};

TessellationView tessellationViewOf(const CameraView& camera, uint64_t id);

// Why `camera` would tessellate the casters differently from `view` beyond
// the tolerance ("scale 1.31x at a corner", "turned 12.0 degrees"), or
// nothing when it would not.
std::optional<std::string> tessellationDrift(const TessellationView& view, const CameraView& camera,
                                             const CasterBounds& casters);

}  // namespace hdhair
