#include "hdHair/environment/DomeLightSampling.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "hdHair/environment/LatlongDirections.h"

namespace hdhair {

namespace {

double luminance(const glm::vec3& rgb) { return 0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b; }

// The radical inverse of k in `base`: the van der Corput sequence, in [0, 1).
double radicalInverse(unsigned k, unsigned base) {
    double inverse = 0.0, scale = 1.0 / base;
    for (; k > 0; k /= base, scale /= base) inverse += double(k % base) * scale;
    return inverse;
}

}  // namespace

std::vector<SampledDomeLight> sampleDomeLights(const RadianceGrid& grid, const glm::dmat4& domeToWorld, int count) {
    if (count < 1 || count > kMaxSampledDomeLights)
        throw std::invalid_argument("sampleDomeLights: " + std::to_string(count) + " lights asked for, not 1 to " +
                                    std::to_string(kMaxSampledDomeLights));
    std::vector<double> cumulative(grid.cellCount());
    double total = 0.0;
    for (size_t c = 0; c < grid.cellCount(); ++c) {
        total += std::max(0.0, luminance(grid.radiance[c])) * double(grid.solidAngles[c]);
        cumulative[c] = total;
    }
    if (!(total > 0.0) || !std::isfinite(total)) return {};

    constexpr double pi = 3.14159265358979323846;
    std::vector<SampledDomeLight> lights;
    lights.reserve(size_t(count));
    for (int k = 0; k < count; ++k) {
        const double target = (double(k) + 0.5) / double(count) * total;
        size_t c = std::min(size_t(std::upper_bound(cumulative.begin(), cumulative.end(), target) -
                                   cumulative.begin()),
                            grid.cellCount() - 1);
        // Rounding can put the last target past the final cell with light.
        while (c > 0 && cumulative[c] == cumulative[c - 1]) --c;
        const int x = int(c % size_t(grid.width)), y = int(c / size_t(grid.width));
        // Uniform in the cell's solid angle: u uniform, cos θ uniform between the row's edges (θ = πv).
        const double u = (double(x) + radicalInverse(unsigned(k), 2)) / double(grid.width);
        const double cosTop = std::cos(pi * double(y) / double(grid.height));
        const double cosBottom = std::cos(pi * double(y + 1) / double(grid.height));
        const double cosTheta = cosTop + (cosBottom - cosTop) * radicalInverse(unsigned(k), 3);
        const double v = std::acos(std::clamp(cosTheta, -1.0, 1.0)) / pi;
        SampledDomeLight light;
        light.direction = domeLightDirectionToWorld(domeToWorld, latlongDirection(float(u), float(v)));
        light.irradiance = grid.radiance[c] * float(total / (double(count) * luminance(grid.radiance[c])));
        lights.push_back(light);
    }
    return lights;
}

RadianceGrid uniformDomeGrid(const glm::vec3& radiance, int width, int height) {
    RadianceGrid grid = latlongGrid(width, height);
    std::fill(grid.radiance.begin(), grid.radiance.end(), radiance);
    return grid;
}

}  // namespace hdhair
