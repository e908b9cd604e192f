#include "hdHair/shading/SrbfUniformDome.h"

#include <algorithm>
#include <cmath>

#include "hdHair/environment/Srbf.h"

namespace hdhair {

namespace {

constexpr double kPi = 3.141592653589793;

// Trapezoid weight of node k of n over an interval of length `length`.
double trapezoid(int k, int n, double length) {
    const double step = length / double(n - 1);
    return (k == 0 || k == n - 1) ? 0.5 * step : step;
}

}  // namespace

std::vector<glm::vec3> srbfUniformDomeResponse(const SrbfConvolutionTable& table) {
    const SrbfTableResolution& r = table.resolution;
    const int W = table.width(), H = table.height(), C = table.channels;
    std::vector<glm::vec3> response(size_t(H), glm::vec3(0.0f));
    const int slab = r.bandwidths - 1;  // λ = 16
    const double kernelIntegral = srbfIntegral(double(kMinSrbfBandwidth));
    for (int y = 0; y < H; ++y) {
        glm::dvec3 sum(0.0);
        for (int k = 0; k < r.centres; ++k) {
            const double thetaXi = -0.5 * kPi + kPi * double(k) / double(r.centres - 1);
            const double wXi = std::cos(thetaXi) * trapezoid(k, r.centres, kPi);
            const size_t z = size_t(slab * r.centres + k);
            for (int x = 0; x < W; ++x) {
                // ψ over [0, π], counted twice for [π, 2π]; one node (Kajiya-Kay) spans all of it.
                const double wPsi = 2.0 * (W == 1 ? kPi : trapezoid(x, W, kPi));
                const size_t at = ((z * size_t(H) + size_t(y)) * size_t(W) + size_t(x)) * size_t(C);
                for (int c = 0; c < std::min(C, 3); ++c) sum[c] += wXi * wPsi * double(table.texels[at + size_t(c)]);
            }
        }
        response[size_t(y)] = glm::vec3(sum / kernelIntegral);
    }
    return response;
}

glm::vec3 sampleSrbfUniformDome(const std::vector<glm::vec3>& response, float thetaO) {
    if (response.empty()) return glm::vec3(0.0f);
    const int n = int(response.size());
    double u = (double(thetaO) + 0.5 * kPi) / kPi * double(n - 1);
    u = std::clamp(std::isfinite(u) ? u : 0.0, 0.0, double(n - 1));
    const int i0 = std::min(int(u), n - 1), i1 = std::min(i0 + 1, n - 1);
    const float w = float(u - double(i0));
    return response[size_t(i0)] * (1.0f - w) + response[size_t(i1)] * w;
}

}  // namespace hdhair
