#pragma once
// Uniform Catmull-Rom (tension 0.5) evaluation of one prepared segment: the
// same weights the GPU tessellation shader uses, so CPU code (tests, picking,
// bounds checks) sees exactly the curve that is drawn. u runs from the
// segment's 2nd control (u = 0) to its 3rd (u = 1). (HdSt's basisCurves.glslfx
// uses the same cubic with u reversed.)

#include <array>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "hdHair/curves/PreparedCurves.h"

namespace hdhair {

// Weights of controls C0..C3 at u in [0, 1]; they sum to 1.
inline std::array<float, 4> catmullRomWeights(float u) {
    const float u2 = u * u;
    const float u3 = u2 * u;
    return {-0.5f * u3 + u2 - 0.5f * u,
            1.5f * u3 - 2.5f * u2 + 1.0f,
            -1.5f * u3 + 2.0f * u2 + 0.5f * u,
            0.5f * u3 - 0.5f * u2};
}

// d/du of catmullRomWeights; they sum to 0.
inline std::array<float, 4> catmullRomDerivativeWeights(float u) {
    const float u2 = u * u;
    return {-1.5f * u2 + 2.0f * u - 0.5f,
            4.5f * u2 - 5.0f * u,
            -4.5f * u2 + 4.0f * u + 0.5f,
            1.5f * u2 - 1.0f * u};
}

// The length of a segment's Bezier control polygon B0 = C1,
// B1 = C1 + (C2 - C0)/6, B2 = C2 - (C3 - C1)/6, B3 = C2, which bounds the
// segment's length (the curve lies in the polygon's hull; strand.tesc cuts
// by the same bound).
inline float bezierPolygonLength(const StrandControlPoint* controls) {
    const glm::vec3 b0 = controls[1].position, b3 = controls[2].position;
    const glm::vec3 b1 = b0 + (controls[2].position - controls[0].position) / 6.0f;
    const glm::vec3 b2 = b3 - (controls[3].position - controls[1].position) / 6.0f;
    return glm::length(b1 - b0) + glm::length(b2 - b1) + glm::length(b3 - b2);
}

// Position, width, colour and opacity of a segment (4 consecutive controls) at u.
inline StrandControlPoint evaluate(const StrandControlPoint* controls, float u) {
    const std::array<float, 4> w = catmullRomWeights(u);
    StrandControlPoint result{glm::vec3(0.0f), 0.0f, glm::vec3(0.0f), 0.0f};
    for (int i = 0; i < 4; ++i) {
        result.position += w[i] * controls[i].position;
        result.width += w[i] * controls[i].width;
        result.color += w[i] * controls[i].color;
        result.opacity += w[i] * controls[i].opacity;
    }
    return result;
}

// d(position)/du of a segment at u: the curve's tangent, not normalised.
inline glm::vec3 evaluateTangent(const StrandControlPoint* controls, float u) {
    const std::array<float, 4> w = catmullRomDerivativeWeights(u);
    glm::vec3 tangent(0.0f);
    for (int i = 0; i < 4; ++i) tangent += w[i] * controls[i].position;
    return tangent;
}

}  // namespace hdhair
