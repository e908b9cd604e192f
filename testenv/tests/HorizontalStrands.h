#pragma once
// Straight strands for scenes built in code, whose pixels follow by hand:
// linear curves along x from -5 to 5 (across any of the tests' views), one
// curve per height y, at depth z, of constant width, colour and opacity.
// Curve i is elementId i.

#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "hdHair/scene/CurvesPrim.h"
#include "hdHair/scene/tests/AuthoredPrimvar.h"

namespace hdhair::testenv {

inline CurvesPrim horizontalStrands(const std::string& path, int primId, int instanceId, float z,
                                    const std::vector<double>& heights, double width, glm::vec3 color,
                                    float opacity) {
    CurvesPrim prim;
    prim.path = path;
    prim.primId = primId;
    prim.instanceId = instanceId;
    prim.type = CurveType::Linear;
    for (double y : heights) {
        prim.curveVertexCounts.push_back(2);
        prim.points.push_back({-5.0f, float(y), z});
        prim.points.push_back({5.0f, float(y), z});
    }
    using hdhair::test::authoredPrimvar;
    prim.primvars["widths"] = authoredPrimvar("widths", Interpolation::Constant, 1, {float(width)});
    prim.primvars["displayColor"] =
        authoredPrimvar("displayColor", Interpolation::Constant, 3, {color.r, color.g, color.b});
    prim.primvars["displayOpacity"] = authoredPrimvar("displayOpacity", Interpolation::Constant, 1, {opacity});
    return prim;
}

}  // namespace hdhair::testenv
