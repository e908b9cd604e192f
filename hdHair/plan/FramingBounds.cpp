#include "hdHair/plan/FramingBounds.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <glm/common.hpp>
#include <glm/vector_relational.hpp>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/curves/PreparedCurves.h"
#include "hdHair/scene/MeshPrim.h"
#include "hdHair/scene/SceneValidation.h"

namespace hdhair {

namespace {

bool isFinite(const glm::dvec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

// The value at `fraction` of the sorted order (nth_element: O(n)).
double quantile(std::vector<double>& values, double fraction) {
    const size_t index = std::min(values.size() - 1, size_t(fraction * double(values.size() - 1) + 0.5));
    std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(index), values.end());
    return values[index];
}

}  // namespace

SceneBounds framingBounds(const std::vector<FramingPoints>& prims, Diagnostics& diagnostics) {
    glm::dvec3 q1(0.0), q3(0.0);
    std::vector<double> coordinates;
    for (int axis = 0; axis < 3; ++axis) {
        coordinates.clear();
        for (const FramingPoints& prim : prims)
            for (const glm::dvec3& p : prim.points)
                if (isFinite(p)) coordinates.push_back(p[axis]);
        if (coordinates.empty()) return SceneBounds{};
        q1[axis] = quantile(coordinates, 0.25);
        q3[axis] = quantile(coordinates, 0.75);
    }
    const double spread = std::max({q3.x - q1.x, q3.y - q1.y, q3.z - q1.z});
    const glm::dvec3 low = q1 - kOutlierSpreads * spread, high = q3 + kOutlierSpreads * spread;

    SceneBounds bounds;
    for (const FramingPoints& prim : prims) {
        size_t outliers = 0;
        glm::dvec3 first(0.0);
        for (const glm::dvec3& p : prim.points) {
            // A point that is not finite here overflowed on the way (a span
            // box around a point near float's limit): an outlier too.
            if (!isFinite(p) ||
                (spread > 0.0 && (glm::any(glm::lessThan(p, low)) || glm::any(glm::greaterThan(p, high))))) {
                if (outliers++ == 0) first = p;
                continue;
            }
            const bool none = bounds.empty();
            bounds.min = none ? p : glm::min(bounds.min, p);
            bounds.max = none ? p : glm::max(bounds.max, p);
        }
        if (outliers > 0)
            diagnostics.warn(prim.path, fmt::format("{} point(s) lie more than {} times the stage's interquartile "
                                                    "spread ({:g}) outside its other points, the first at ({:g}, "
                                                    "{:g}, {:g}); the framing camera leaves them out (--camera "
                                                    "frames them as you choose)",
                                                    outliers, kOutlierSpreads, spread, first.x, first.y, first.z));
    }
    return bounds;
}

FramingPoints spanFramingPoints(const PreparedCurves& curves) {
    FramingPoints prim{curves.path, {}};
    prim.points.reserve(2 * curves.segmentCount());
    for (size_t s = 0; s < curves.segmentCount(); ++s) {
        glm::vec3 low(std::numeric_limits<float>::max()), high(-std::numeric_limits<float>::max());
        growBoundsBySpan(curves.spanControls(s), low, high);
        prim.points.emplace_back(low);
        prim.points.emplace_back(high);
    }
    return prim;
}

FramingPoints meshFramingPoints(const MeshPrim& mesh) {
    FramingPoints prim{mesh.path, {}};
    if (!isFiniteTransform(mesh.worldTransform)) return prim;
    prim.points.reserve(mesh.points.size());
    for (const glm::vec3& point : mesh.points)
        prim.points.emplace_back(mesh.worldTransform * glm::dvec4(glm::dvec3(point), 1.0));
    return prim;
}

}  // namespace hdhair
