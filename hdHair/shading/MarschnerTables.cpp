#include "hdHair/shading/MarschnerTables.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <glm/gtc/packing.hpp>

namespace hdhair {
namespace {

constexpr float kPiF = 3.14159265358979323846f;

float roundToHalf(float x) { return glm::unpackHalf1x16(glm::packHalf1x16(x)); }

// Bilinear fetch of one RGBA layer at normalised (s, t), texel centres,
// clamp to edge (OpenGL 4.6 §8.14.2 with GL_LINEAR, GL_CLAMP_TO_EDGE).
void fetchBilinear(const MarschnerTables& tables, int layer, float s, float t, float out[4]) {
    auto axis = [](float coordinate, int size, int& i0, int& i1, float& weight) {
        float u = std::clamp(std::isfinite(coordinate) ? coordinate : 0.0f, 0.0f, 1.0f) * float(size) - 0.5f;
        float base = std::floor(u);
        weight = u - base;
        i0 = std::clamp(int(base), 0, size - 1);
        i1 = std::clamp(int(base) + 1, 0, size - 1);
    };
    int x0, x1, y0, y1;
    float wx, wy;
    axis(s, tables.width, x0, x1, wx);
    axis(t, tables.height, y0, y1, wy);
    auto texel = [&](int x, int y, int c) {
        return tables.texels[(std::size_t(layer * tables.height + y) * tables.width + x) * 4 + c];
    };
    for (int c = 0; c < 4; ++c) {
        float top = texel(x0, y0, c) * (1.0f - wx) + texel(x1, y0, c) * wx;
        float bottom = texel(x0, y1, c) * (1.0f - wx) + texel(x1, y1, c) * wx;
        out[c] = top * (1.0f - wy) + bottom * wy;
    }
}

}  // namespace

std::vector<std::uint16_t> MarschnerTables::halfTexels() const {
    std::vector<std::uint16_t> result(texels.size());
    for (std::size_t i = 0; i < texels.size(); ++i) result[i] = glm::packHalf1x16(texels[i]);
    return result;
}

MarschnerTables buildMarschnerTables(const MarschnerParameters& parameters, int width, int height,
                                     MarschnerTablePrecision precision) {
    MarschnerTables tables;
    tables.width = std::max(1, width);
    tables.height = std::max(1, height);
    tables.precision = precision;
    tables.texels.assign(std::size_t(tables.width) * tables.height * 2 * 4, 0.0f);
    for (int y = 0; y < tables.height; ++y) {
        float cosThetaR = (float(y) + 0.5f) / float(tables.height);
        for (int x = 0; x < tables.width; ++x) {
            float phi = (float(x) + 0.5f) / float(tables.width) * kPiF;
            glm::vec3 nR = marschnerAzimuthal(0, phi, cosThetaR, parameters);
            glm::vec3 nTT = marschnerAzimuthal(1, phi, cosThetaR, parameters);
            glm::vec3 nTRT = marschnerAzimuthal(2, phi, cosThetaR, parameters);
            float layer0[4] = {nTT.x, nTT.y, nTT.z, nR.x};
            float layer1[4] = {nTRT.x, nTRT.y, nTRT.z, 0.0f};
            for (int c = 0; c < 4; ++c) {
                std::size_t i0 = (std::size_t(y) * tables.width + x) * 4 + c;
                std::size_t i1 = (std::size_t(tables.height + y) * tables.width + x) * 4 + c;
                bool half = precision == MarschnerTablePrecision::Half;
                tables.texels[i0] = half ? roundToHalf(layer0[c]) : layer0[c];
                tables.texels[i1] = half ? roundToHalf(layer1[c]) : layer1[c];
            }
        }
    }
    return tables;
}

MarschnerAzimuthalTerms sampleMarschnerTables(const MarschnerTables& tables, float phi, float cosThetaR) {
    MarschnerAzimuthalTerms terms;
    if (tables.width <= 0 || tables.height <= 0 || tables.texels.empty()) return terms;
    float s = std::abs(phi) / kPiF, t = std::abs(cosThetaR);
    float layer0[4], layer1[4];
    fetchBilinear(tables, 0, s, t, layer0);
    fetchBilinear(tables, 1, s, t, layer1);
    terms.TT = glm::vec3(layer0[0], layer0[1], layer0[2]);
    terms.R = glm::vec3(layer0[3]);
    terms.TRT = glm::vec3(layer1[0], layer1[1], layer1[2]);
    return terms;
}

MarschnerLobes evaluateMarschnerTabled(const glm::vec3& t, const glm::vec3& wi, const glm::vec3& wo,
                                       const MarschnerParameters& parameters, const MarschnerTables& tables) {
    MarschnerAngles angles = marschnerAngles(t, wi, wo);
    MarschnerAzimuthalTerms n = sampleMarschnerTables(tables, angles.phi, angles.cosThetaR);
    return combineMarschnerLobes(angles, n.R, n.TT, n.TRT, parameters);
}

std::vector<MarschnerTableError> measureMarschnerTableErrors(const MarschnerParameters& parameters,
                                                             const std::vector<int>& sizes, int directions,
                                                             int gridSize) {
    // The directions: uniform on the sphere for t, ωi and ωo (same seed for
    // every candidate), their analytic values computed once.
    std::mt19937 random(20030727);
    std::normal_distribution<float> gaussian;
    auto randomDirection = [&] { return glm::vec3(gaussian(random), gaussian(random), gaussian(random)); };
    std::vector<glm::vec3> ts, wis, wos, reference;
    for (int i = 0; i < directions; ++i) {
        ts.push_back(randomDirection());
        wis.push_back(randomDirection());
        wos.push_back(randomDirection());
        reference.push_back(evaluateMarschner(ts.back(), wis.back(), wos.back(), parameters).radiance());
    }
    // The grid: gridSize² points of (φ, cos θ_r); an odd count avoids most
    // texel centres of power-of-two tables.
    std::vector<MarschnerAzimuthalTerms> gridReference;
    int g = std::max(2, gridSize);
    for (int y = 0; y < g; ++y)
        for (int x = 0; x < g; ++x) {
            float phi = float(x) / float(g - 1) * kPiF, s = float(y) / float(g - 1);
            gridReference.push_back({marschnerAzimuthal(0, phi, s, parameters), marschnerAzimuthal(1, phi, s, parameters),
                                     marschnerAzimuthal(2, phi, s, parameters)});
        }
    std::vector<MarschnerTableError> errors;
    for (int size : sizes) {
        for (MarschnerTablePrecision precision : {MarschnerTablePrecision::Half, MarschnerTablePrecision::Float}) {
            MarschnerTables tables = buildMarschnerTables(parameters, size, size, precision);
            MarschnerTableError error;
            error.width = error.height = size;
            error.precision = precision;
            double sumSquares = 0.0;
            for (int i = 0; i < directions; ++i) {
                glm::vec3 tabled = evaluateMarschnerTabled(ts[i], wis[i], wos[i], parameters, tables).radiance();
                for (int c = 0; c < 3; ++c) {
                    float difference = std::abs(tabled[c] - reference[i][c]);
                    error.maxAbsolute = std::max(error.maxAbsolute, difference);
                    error.peak = std::max(error.peak, reference[i][c]);
                    sumSquares += double(difference) * difference;
                }
            }
            error.rms = float(std::sqrt(sumSquares / std::max(1, 3 * directions)));
            double gridSquares = 0.0;
            for (int y = 0; y < g; ++y)
                for (int x = 0; x < g; ++x) {
                    float phi = float(x) / float(g - 1) * kPiF, s = float(y) / float(g - 1);
                    MarschnerAzimuthalTerms tabled = sampleMarschnerTables(tables, phi, s);
                    const MarschnerAzimuthalTerms& exact = gridReference[std::size_t(y) * g + x];
                    for (int c = 0; c < 3; ++c)
                        for (auto pair : {std::make_pair(tabled.R[c], exact.R[c]), std::make_pair(tabled.TT[c], exact.TT[c]),
                                          std::make_pair(tabled.TRT[c], exact.TRT[c])}) {
                            float difference = std::abs(pair.first - pair.second);
                            error.azimuthalMaxAbsolute = std::max(error.azimuthalMaxAbsolute, difference);
                            error.azimuthalPeak = std::max(error.azimuthalPeak, pair.second);
                            gridSquares += double(difference) * difference;
                        }
                }
            error.azimuthalRms = float(std::sqrt(gridSquares / (9.0 * g * g)));
            errors.push_back(error);
        }
    }
    return errors;
}

}  // namespace hdhair
