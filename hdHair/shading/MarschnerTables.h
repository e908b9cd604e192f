#pragma once
// The azimuthal part of the Marschner model (Marschner.h), precomputed per
// material into the tables the GPU samples (shaders/include/marschner.glsl),
// and the CPU mirror of that lookup.
//
// Layout (what the renderer uploads; README "GPU table layout"):
//   one GL_TEXTURE_2D_ARRAY, 2 layers, internal format GL_RGBA16F (half) or
//   GL_RGBA32F, width W × height H, GL_LINEAR min/mag, no mipmaps,
//   GL_CLAMP_TO_EDGE on s and t.
//   layer 0: rgb = N_TT(φ, θ_r) per channel, a = N_R(φ, θ_r) (colourless)
//   layer 1: rgb = N_TRT(φ, θ_r) per channel (caustic treated), a = 0
//   s (x, width)  = φ/π,        φ = |φ_r − φ_i| ∈ [0, π]
//   t (y, height) = cos θ_r = √(1 − (t·ωo)²) ∈ [0, 1]
//   texel (x, y) holds the value at its centre s = (x + ½)/W, t = (y + ½)/H.
// σ_a, η and the caustic parameters are baked in: rebuild when they change.
// α_p and β_p are not (M_p is evaluated analytically per fragment).
//
// Size and precision chosen by measureMarschnerTableErrors() (README): 64×64
// RGBA16F — the smallest size whose error on the scattered radiance is below
// 1 % of its peak; half precision adds < 0.1 % of peak at that size.

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "hdHair/shading/Marschner.h"

namespace hdhair {

enum class MarschnerTablePrecision { Half, Float };

constexpr int kMarschnerTableWidth = 64;   // φ axis
constexpr int kMarschnerTableHeight = 64;  // cos θ_r axis
constexpr MarschnerTablePrecision kMarschnerTablePrecision = MarschnerTablePrecision::Half;

struct MarschnerTables {
    int width = 0, height = 0;
    MarschnerTablePrecision precision = MarschnerTablePrecision::Half;
    // RGBA texels, layer-major then row-major: texel (x, y) of layer l starts
    // at index ((l·height + y)·width + x)·4. Already rounded to half when
    // precision is Half, so CPU lookups see what the GPU sees.
    std::vector<float> texels;
    // The same texels as IEEE half floats for glTexImage3D(…, GL_HALF_FLOAT, …).
    std::vector<std::uint16_t> halfTexels() const;
};

MarschnerTables buildMarschnerTables(const MarschnerParameters& parameters, int width = kMarschnerTableWidth,
                                     int height = kMarschnerTableHeight,
                                     MarschnerTablePrecision precision = kMarschnerTablePrecision);

struct MarschnerAzimuthalTerms {
    glm::vec3 R{0.0f}, TT{0.0f}, TRT{0.0f};
};

// Bilinear lookup at (φ, cos θ_r) as the GPU sampler does it: texel
// centres, clamp to edge.
MarschnerAzimuthalTerms sampleMarschnerTables(const MarschnerTables& tables, float phi, float cosThetaR);

// The model with N_p from the tables: the formula of marschner.glsl.
MarschnerLobes evaluateMarschnerTabled(const glm::vec3& t, const glm::vec3& wi, const glm::vec3& wo,
                                       const MarschnerParameters& parameters, const MarschnerTables& tables);

struct MarschnerTableError {
    int width = 0, height = 0;
    MarschnerTablePrecision precision = MarschnerTablePrecision::Half;
    // Over `directions` random (t, ωi, ωo): the radiance R + TT + TRT per
    // channel, tabled minus analytic.
    float maxAbsolute = 0.0f, rms = 0.0f;
    float peak = 0.0f;  // max analytic radiance over the same set
    // Over a dense (φ, cos θ_r) grid offset from every table's texel centres:
    // the azimuthal terms N_p alone.
    float azimuthalMaxAbsolute = 0.0f, azimuthalRms = 0.0f, azimuthalPeak = 0.0f;
};

// Errors of the tabled model against the analytic one, for every size in
// `sizes` (square tables) in half and float. Deterministic.
std::vector<MarschnerTableError> measureMarschnerTableErrors(const MarschnerParameters& parameters,
                                                             const std::vector<int>& sizes, int directions = 20000,
                                                             int gridSize = 301);

}  // namespace hdhair
