#include "hdHair/plan/ShadowLightView.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

namespace hdhair {

bool ShadowLightView::operator==(const ShadowLightView& other) const {
    return valid == other.valid && fallback == other.fallback && needsCubeMap == other.needsCubeMap &&
           orthographic == other.orthographic &&
           view == other.view && projection == other.projection && eye == other.eye && forward == other.forward &&
           nearDepth == other.nearDepth && farDepth == other.farDepth && texelSize == other.texelSize &&
           resolution == other.resolution && pixelsPerUnit == other.pixelsPerUnit;
}

namespace {

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

bool finite(const glm::dmat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

// The bounds grown by half the widest strand: a ribbon's edge reaches that
// far past its centre line.
struct Box {
    glm::dvec3 min, max;
    glm::dvec3 corner(int i) const {
        return {(i & 1) ? max.x : min.x, (i & 2) ? max.y : min.y, (i & 4) ? max.z : min.z};
    }
    glm::dvec3 centre() const { return 0.5 * (min + max); }
    double diagonal() const { return glm::length(max - min); }
};

// Any unit vector not parallel to `forward`, for lookAt.
glm::dvec3 upFor(const glm::dvec3& forward) {
    return std::abs(forward.y) < 0.99 ? glm::dvec3(0.0, 1.0, 0.0) : glm::dvec3(1.0, 0.0, 0.0);
}

// One texel of margin on each side: a ribbon whose centre lies on the
// bounds' edge still lands inside the map.
double withTexelMargin(double half, int resolution) {
    return half * double(resolution) / double(std::max(resolution - 2, 1));
}

ShadowLightView invalid(std::string why) {
    ShadowLightView view;
    view.fallback = std::move(why);
    return view;
}

ShadowLightView finish(ShadowLightView view, int resolution) {
    view.resolution = resolution;
    view.pixelsPerUnit = view.projection[0][0] * double(resolution) * 0.5;
    view.valid = finite(view.view) && finite(view.projection) && finite(view.eye) && finite(view.forward) &&
                 std::isfinite(view.nearDepth) && std::isfinite(view.farDepth) && view.farDepth > view.nearDepth &&
                 std::isfinite(view.texelSize) && view.texelSize > 0.0 && view.pixelsPerUnit > 0.0;
    if (!view.valid) return invalid("the light's view of the hair is not finite (degenerate transform or bounds)");
    return view;
}

ShadowLightView distantView(const glm::dvec3& towardsLight, const Box& box, int resolution) {
    ShadowLightView view;
    view.orthographic = true;
    view.forward = -towardsLight;
    const glm::dvec3 centre = box.centre();
    const double diagonal = box.diagonal();
    // A flat or point-like set of casters still gets a window and a depth
    // range: never a zero-size projection.
    const double pad = std::max(1e-4 * diagonal, 1e-6 * std::max(1.0, glm::length(centre)));
    glm::dmat4 lookAt = glm::lookAtRH(centre, centre + view.forward, upFor(view.forward));
    double half = 0.0, low = 0.0, high = 0.0;
    for (int i = 0; i < 8; ++i) {
        glm::dvec3 p = glm::dvec3(lookAt * glm::dvec4(box.corner(i), 1.0));
        half = std::max({half, std::abs(p.x), std::abs(p.y)});
        low = std::min(low, p.z);   // the view looks down its -z
        high = std::max(high, p.z);
    }
    half = withTexelMargin(std::max(half, pad), resolution);
    // The eye sits `pad` in front of the nearest corner.
    view.eye = centre - view.forward * (high + pad);
    view.view = glm::lookAtRH(view.eye, view.eye + view.forward, upFor(view.forward));
    view.nearDepth = pad;
    view.farDepth = pad + std::max(high - low, pad);  // all hair at one depth: still a range
    view.projection = glm::orthoRH_NO(-half, half, -half, half, 0.0, view.farDepth + pad);
    view.texelSize = 2.0 * half / double(resolution);
    return finish(view, resolution);
}

// A perspective view from `eye` along `forward` with half-angle
// atan(tanHalf), holding the box's depth range in front of the eye.
ShadowLightView perspectiveView(const glm::dvec3& eye, const glm::dvec3& forward, double tanHalf, const Box& box,
                                int resolution) {
    ShadowLightView view;
    view.orthographic = false;
    view.eye = eye;
    view.forward = forward;
    view.view = glm::lookAtRH(eye, eye + forward, upFor(forward));
    double nearest = INFINITY, farthest = 0.0;
    for (int i = 0; i < 8; ++i) {
        double depth = glm::dot(box.corner(i) - eye, forward);
        nearest = std::min(nearest, depth);
        farthest = std::max(farthest, depth);
    }
    // A light among the hair (a narrow spot inside the bounds) sees from
    // right in front of itself; linear depth keeps full precision anyway.
    view.nearDepth = std::max(nearest, 1e-4 * farthest);
    view.farDepth = std::max(farthest, view.nearDepth * (1.0 + 1e-4));  // a point still gets a range
    tanHalf = withTexelMargin(tanHalf, resolution);
    view.projection = glm::perspectiveRH_NO(2.0 * std::atan(tanHalf), 1.0, view.nearDepth * 0.999,
                                            view.farDepth * 1.001);
    view.texelSize = 2.0 * tanHalf / double(resolution);
    return finish(view, resolution);
}

// How wide a frustum from `eye` along `forward` must be for every corner;
// infinity when a corner is at or behind the eye.
double tanHalfHolding(const glm::dvec3& eye, const glm::dvec3& forward, const Box& box) {
    glm::dmat4 lookAt = glm::lookAtRH(eye, eye + forward, upFor(forward));
    const double touching = 1e-6 * std::max(box.diagonal(), 1e-12);
    double tanHalf = 0.0;
    for (int i = 0; i < 8; ++i) {
        glm::dvec3 p = glm::dvec3(lookAt * glm::dvec4(box.corner(i), 1.0));
        if (-p.z <= touching) return INFINITY;
        tanHalf = std::max({tanHalf, std::abs(p.x) / -p.z, std::abs(p.y) / -p.z});
    }
    return tanHalf;
}

}  // namespace

CasterBounds unite(const CasterBounds& a, const CasterBounds& b) {
    if (a.empty()) return CasterBounds{b.min, b.max, std::max(a.maxWidth, b.maxWidth)};
    if (b.empty()) return CasterBounds{a.min, a.max, std::max(a.maxWidth, b.maxWidth)};
    return CasterBounds{glm::min(a.min, b.min), glm::max(a.max, b.max), std::max(a.maxWidth, b.maxWidth)};
}

ShadowLightView fitShadowLightView(const ShadingLight& light, const CasterBounds& casters, int resolution) {
    if (casters.empty()) return invalid("nothing casts");
    const double margin = 0.5 * (std::isfinite(casters.maxWidth) ? std::max(casters.maxWidth, 0.0) : 0.0);
    const Box box{casters.min - margin, casters.max + margin};
    if (!finite(box.min) || !finite(box.max)) return invalid("the hair's bounds are not finite");
    resolution = std::max(resolution, 1);
    const glm::dvec3 vector(light.directionOrPosition);
    if (!finite(vector)) return invalid("the light's transform is not finite");

    if (!light.isLocal) {
        const double length = glm::length(vector);
        if (!(length > 0.0)) return invalid("the light has no direction");
        return distantView(vector / length, box, resolution);
    }

    const double maxTanHalf = std::tan(glm::radians(kMaxShadowHalfFieldOfViewDegrees));
    const glm::dvec3 toCentre = box.centre() - vector;
    double tanHalf = INFINITY;
    glm::dvec3 aim(0.0, 0.0, -1.0);
    if (glm::length(toCentre) > 0.0) {
        aim = glm::normalize(toCentre);
        tanHalf = tanHalfHolding(vector, aim, box);
    }
    // A cone narrower than what the bounds need holds everything the light
    // can reach: aim along the axis, as wide as the cone.
    const glm::dvec3 axis(light.emissionAxis);
    if (light.shaped && finite(axis) && glm::length(axis) > 0.0) {
        const double coneTanHalf = std::tan(std::acos(std::clamp(double(light.coneCosOuter), -1.0, 1.0)));
        if (coneTanHalf >= 0.0 && coneTanHalf < tanHalf) {
            tanHalf = coneTanHalf;
            aim = glm::normalize(axis);
        }
    }
    if (!(tanHalf <= maxTanHalf)) {
        ShadowLightView view = invalid(fmt::format(
            "the light is inside or too close to the hair's bounds: one perspective view would need more than "
            "{} degrees either side (a cube map); shaded without its shadows (shadowMode=auto or volume shadow it "
            "through the hair's density volume)",
            kMaxShadowHalfFieldOfViewDegrees));
        view.needsCubeMap = true;
        return view;
    }
    // A cone wholly behind the hair's depth range lights none of it.
    double farthest = 0.0;
    for (int i = 0; i < 8; ++i) farthest = std::max(farthest, glm::dot(box.corner(i) - vector, aim));
    if (!(farthest > 0.0)) return invalid("the hair is behind the light: it lights none of it");
    return perspectiveView(vector, aim, std::max(tanHalf, 1e-6), box, resolution);
}

}  // namespace hdhair
