#pragma once
// hdHair's scene-linear rendering spaces and the one place their primaries
// are written down: the renderingSpace setting's names (as hdHair's OCIO
// config names the spaces), the matrices between them, and the chromaticities
// an EXR records for each.
//
// Authored colours are linear Rec.709 (USD's default for colours without
// colorSpace metadata); a frame rendered in ACEScg takes every colour through
// kRec709ToAp1 once, before shading (Renderer), and its images are ACEScg.

#include <array>
#include <string>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "hdHair/base/TokenTable.h"

namespace hdhair {

constexpr const char* kLinearRec709 = "lin_rec709";
constexpr const char* kAcesCg = "ACEScg";

enum class RenderingSpace { LinearRec709, AcesCg };
template <>
struct TokenTable<RenderingSpace> {
    static constexpr std::array<TokenName<RenderingSpace>, 2> names{
        {{RenderingSpace::LinearRec709, kLinearRec709}, {RenderingSpace::AcesCg, kAcesCg}}};
};

using Matrix3 = std::array<std::array<double, 3>, 3>;  // rows

// Linear Rec.709 (D65) to ACES AP1 (ACEScg, D60), the white adapted with
// Bradford's transform: the matrix colour-science's
// matrix_RGB_to_RGB(sRGB, ACEScg, 'Bradford') gives, and the inverse of
// OpenColorIO's built-in "UTILITY - ACES-AP1_to_LINEAR-REC709_BFD" (which
// hdHair's config uses for lin_rec709; testColorSpaces checks both ways).
// Every row sums to 1 within 1e-8: equal RGB (grey) stays grey.
constexpr Matrix3 kRec709ToAp1 = {{{0.6130974024, 0.3395231462, 0.0473794514},
                                   {0.0701937225, 0.9163538791, 0.0134523985},
                                   {0.0206155929, 0.1095697729, 0.8698146341}}};
// Its inverse, OCIO's "UTILITY - ACES-AP1_to_LINEAR-REC709_BFD" as published.
constexpr Matrix3 kAp1ToRec709 = {{{1.70505099, -0.62179212, -0.08325887},
                                   {-0.13025642, 1.14080474, -0.01054832},
                                   {-0.02400336, -0.12896898, 1.15297233}}};

// The matrix that takes linear Rec.709 into `space` (identity for lin_rec709).
glm::mat3 rec709To(RenderingSpace space);
// `rec709` (a linear Rec.709 colour) in `space`.
glm::vec3 toRenderingSpace(RenderingSpace space, const glm::vec3& rec709);

// The chromaticities (red, green, blue, white xy) an EXR records for the
// space: Rec.709 with D65, or AP1 with the ACES white.
std::array<float, 8> chromaticitiesOf(RenderingSpace space);

}  // namespace hdhair
