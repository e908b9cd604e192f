#include "hdHair/render/TessellationView.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "hdHair/render/CameraView.h"
#include "hdHair/render/ShadowLightView.h"

namespace hdhair {

namespace {

// How a view sees a point: pixels per world unit there, and the direction
// it looks at it from. Points at or behind a perspective eye have no scale.
struct Projected {
    double pixelsPerUnit = 0.0;
    glm::dvec3 direction{0.0};
};

Projected project(const TessellationView& view, const glm::dvec3& point) {
    Projected result;
    const double w = (view.viewProjection * glm::dvec4(point, 1.0)).w;
    if (!(w > 0.0)) return result;
    result.pixelsPerUnit = view.pixelsPerUnit / w;
    const glm::dvec3 offset = point - view.eye;
    result.direction = view.orthographic || glm::length(offset) == 0.0 ? view.forward : glm::normalize(offset);
    return result;
}

}  // namespace

TessellationView tessellationViewOf(const CameraView& camera, uint64_t id) {
    TessellationView view;
    view.viewProjection = camera.projection * camera.view;
    view.viewport = glm::dvec2(camera.imageWidth, camera.imageHeight);
    view.pixelsPerUnit = camera.pixelsPerUnit();
    view.orthographic = camera.orthographic;
    view.eye = camera.position();
    view.forward = camera.forward();
    view.id = id;
    return view;
}

std::optional<std::string> tessellationDrift(const TessellationView& view, const CameraView& camera,
                                             const CasterBounds& casters) {
    if (casters.empty()) return std::nullopt;
    const TessellationView current = tessellationViewOf(camera, 0);
    if (current.viewport != view.viewport) return fmt::format("the image is {}x{} now", camera.imageWidth, camera.imageHeight);
    const double cosTurn = std::cos(glm::radians(kTessellationTurnToleranceDegrees));
    for (int i = 0; i < 9; ++i) {
        const glm::dvec3 point = i == 8 ? 0.5 * (casters.min + casters.max)
                                        : glm::dvec3((i & 1) ? casters.max.x : casters.min.x,
                                                     (i & 2) ? casters.max.y : casters.min.y,
                                                     (i & 4) ? casters.max.z : casters.min.z);
        const Projected before = project(view, point), now = project(current, point);
        if ((before.pixelsPerUnit > 0.0) != (now.pixelsPerUnit > 0.0))
            return std::string("part of the hair crossed the camera's plane");
        if (before.pixelsPerUnit == 0.0) continue;
        const double scale = now.pixelsPerUnit / before.pixelsPerUnit;
        if (!(scale <= kTessellationScaleTolerance && scale >= 1.0 / kTessellationScaleTolerance))
            return fmt::format("a world unit spans {:.2f}x the pixels it did", scale);
        if (!(glm::dot(before.direction, now.direction) >= cosTurn))
            return fmt::format("the view turned {:.1f} degrees",
                               glm::degrees(std::acos(std::clamp(glm::dot(before.direction, now.direction), -1.0, 1.0))));
    }
    return std::nullopt;
}

}  // namespace hdhair
