#include "hdHair/shading/SrbfConvolutionTables.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/packing.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "hdHair/shading/ModifiedBessel.h"

namespace hdhair {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInverseLambdaMin = 1.0 / double(kMaxSrbfBandwidth);  // 1/64
constexpr double kInverseLambdaMax = 1.0 / double(kMinSrbfBandwidth);  // 1/16

// Build quadrature (header): θ_i nodes, N_p azimuth nodes on [0, π], Fourier orders.
constexpr int kInclinationNodes = 360;
constexpr int kAzimuthNodes = 1024;
constexpr int kFourierOrders = 64;
// Below this, e^(−κ)I_n(κ) (and the longitudinal weight) contribute nothing a
// half or float texel can hold.
constexpr double kNegligible = 1e-14;

double node(int i, int count, double low, double high) {
    return count <= 1 ? low : low + (high - low) * double(i) / double(count - 1);
}

SrbfTableResolution sanitised(SrbfTableKind kind, const SrbfTableResolution& resolution) {
    SrbfTableResolution r;
    r.azimuths = kind == SrbfTableKind::KajiyaKay ? 1 : std::max(2, resolution.azimuths);
    r.outgoing = std::max(2, resolution.outgoing);
    r.centres = std::max(2, resolution.centres);
    r.bandwidths = std::max(2, resolution.bandwidths);
    return r;
}

float roundToHalf(float x) { return glm::unpackHalf1x16(glm::packHalf1x16(x)); }

// The inclination quadrature of B_pn: midpoint nodes over [−π/2, π/2].
struct Inclinations {
    std::vector<double> theta, sinTheta, cosTheta;
    double step = kPi / kInclinationNodes;
    Inclinations() {
        for (int k = 0; k < kInclinationNodes; ++k) {
            double t = -0.5 * kPi + (k + 0.5) * step;
            theta.push_back(t);
            sinTheta.push_back(std::sin(t));
            cosTheta.push_back(std::cos(t));
        }
    }
};

// What one θ_o row needs: the longitudinal function of each channel group at
// every θ_i node (M_p for Marschner, the Kajiya-Kay terms' θ dependence) and,
// for Marschner, the cosine-series coefficients a'_pn of N_p(φ; cos θ_o).
struct OutgoingRow {
    std::vector<double> longitudinal[3];  // [group][θ_i node]
    std::vector<glm::dvec3> fourier[3];   // [p][n], a'_p0 = a_p0/2
};

std::vector<OutgoingRow> outgoingRows(SrbfTableKind kind, const SrbfTableResolution& r,
                                      const MarschnerParameters& marschner, float shininess,
                                      const Inclinations& inclinations) {
    std::vector<OutgoingRow> rows(std::size_t(r.outgoing));
    tbb::parallel_for(0, r.outgoing, [&](int y) {
        OutgoingRow& row = rows[std::size_t(y)];
        double thetaO = node(y, r.outgoing, -0.5 * kPi, 0.5 * kPi);
        double sinO = std::sin(thetaO), cosO = std::cos(thetaO);
        if (kind == SrbfTableKind::KajiyaKay) {
            // f = 1/π cos θ_i (diffuse) and 1/π max(0, cos(θ_i + θ_o))^p (specular), KajiyaKay.h.
            for (std::size_t k = 0; k < inclinations.theta.size(); ++k) {
                row.longitudinal[0].push_back(inclinations.cosTheta[k] / kPi);
                double cone = std::max(0.0, std::cos(inclinations.theta[k] + thetaO));
                row.longitudinal[1].push_back(std::pow(cone, std::max(1.0, double(shininess))) / kPi);
            }
            return;
        }
        for (int p = 0; p < 3; ++p) {
            float variance = marschnerLongitudinalVariance(marschner.beta[p]);
            for (std::size_t k = 0; k < inclinations.theta.size(); ++k)
                row.longitudinal[p].push_back(marschnerLongitudinal(float(inclinations.sinTheta[k]),
                                                                    float(inclinations.cosTheta[k]), float(sinO),
                                                                    float(cosO), marschner.alpha[p], variance));
            // a_n = (2/π) ∫_0^π N_p(φ) cos nφ dφ, midpoint rule.
            std::vector<glm::dvec3> samples(kAzimuthNodes);
            for (int j = 0; j < kAzimuthNodes; ++j)
                samples[std::size_t(j)] =
                    glm::dvec3(marschnerAzimuthal(p, float((j + 0.5) * kPi / kAzimuthNodes), float(cosO), marschner));
            row.fourier[p].assign(kFourierOrders + 1, glm::dvec3(0.0));
            for (int n = 0; n <= kFourierOrders; ++n) {
                glm::dvec3 sum(0.0);
                for (int j = 0; j < kAzimuthNodes; ++j)
                    sum += samples[std::size_t(j)] * std::cos(n * (j + 0.5) * kPi / kAzimuthNodes);
                row.fourier[p][std::size_t(n)] = sum * (2.0 / kAzimuthNodes) * (n == 0 ? 0.5 : 1.0);
            }
        }
    });
    return rows;
}

// cos nψ at every ψ node, [node][order] for orders 0..orders.
std::vector<double> azimuthCosines(int W, int orders) {
    std::vector<double> cosines(std::size_t(W) * (orders + 1));
    for (int x = 0; x < W; ++x)
        for (int n = 0; n <= orders; ++n)
            cosines[std::size_t(x) * (orders + 1) + n] = std::cos(n * node(x, W, 0.0, kPi));
    return cosines;
}

// What every texel plane of one table reads.
struct TablePlan {
    SrbfTableKind kind;
    SrbfTableResolution r;
    int W, H, C;
    int orders;  // the Fourier orders kept: 0 for Kajiya-Kay
    int groups;  // the longitudinal functions' channel groups
    const Inclinations& inclinations;
    const std::vector<OutgoingRow>& rows;
    std::vector<double> cosines;  // azimuthCosines
};

// One task's working memory, reused from plane to plane.
struct PlaneScratch {
    std::vector<double> bessel;
    std::vector<double> weight;                 // per θ_i node
    std::vector<int> lastOrder;                 // per θ_i node: the last order summed, −1 for none
    std::vector<std::vector<double>> besselAt;  // per θ_i node: e^(−κ) I_n(κ) up to lastOrder
    std::vector<double> b;                      // B_gn, [group][order]
    std::vector<glm::dvec3> modes;              // per Fourier order

    explicit PlaneScratch(const TablePlan& plan)
        : weight(plan.inclinations.theta.size()), lastOrder(plan.inclinations.theta.size()),
          besselAt(plan.inclinations.theta.size()), b(std::size_t(plan.groups) * (plan.orders + 1)),
          modes(std::size_t(plan.orders + 1)) {}
};

// Fills scratch.weight, lastOrder and besselAt for the plane of bandwidth
// λ centred at θ_ξ.
void weighInclinations(const TablePlan& plan, double lambda, double thetaXi, PlaneScratch& scratch) {
    const Inclinations& inclinations = plan.inclinations;
    const int orders = plan.orders;
    const double cosXi = std::max(0.0, std::cos(thetaXi));
    // Per θ_i node: 2π Δθ cos θ_i exp(λ(cos(θ_i − θ_ξ) − 1)) and e^(−κ) I_n(κ).
    for (std::size_t i = 0; i < inclinations.theta.size(); ++i) {
        scratch.weight[i] = 2.0 * kPi * inclinations.step * inclinations.cosTheta[i] *
                            std::exp(lambda * (std::cos(inclinations.theta[i] - thetaXi) - 1.0));
        scratch.lastOrder[i] = -1;
        if (scratch.weight[i] < kNegligible) continue;
        scaledModifiedBesselI(lambda * inclinations.cosTheta[i] * cosXi, orders, scratch.bessel);
        int last = 0;
        while (last < orders && scratch.bessel[std::size_t(last) + 1] > kNegligible) ++last;
        scratch.lastOrder[i] = last;
        scratch.besselAt[i].assign(scratch.bessel.begin(), scratch.bessel.begin() + last + 1);
    }
}

// Sums scratch.b for one θ_o row from the plane's quadrature.
void sumLongitudinalModes(const TablePlan& plan, const OutgoingRow& row, PlaneScratch& scratch) {
    const int orders = plan.orders;
    std::vector<double>& b = scratch.b;
    // B_gn = Σ_i weight_i · longitudinal_g(θ_i) · e^(−κ_i) I_n(κ_i)
    std::fill(b.begin(), b.end(), 0.0);
    for (std::size_t i = 0; i < plan.inclinations.theta.size(); ++i) {
        if (scratch.lastOrder[i] < 0) continue;
        const double* bi = scratch.besselAt[i].data();
        for (int g = 0; g < plan.groups; ++g) {
            double w = scratch.weight[i] * row.longitudinal[g][i];
            double* bg = &b[std::size_t(g) * (orders + 1)];
            for (int n = 0; n <= scratch.lastOrder[i]; ++n) bg[n] += w * bi[n];
        }
    }
}

// Writes one Marschner row's texels (W of them, C channels each) from scratch.b.
void writeMarschnerRow(const TablePlan& plan, const OutgoingRow& row, PlaneScratch& scratch, float* out) {
    const int orders = plan.orders;
    // Per Fourier mode, the channels: RGB = Σ_p a'_pn B_pn, or (R, TT, TRT) = a'_pn B_pn.
    for (int n = 0; n <= orders; ++n) {
        glm::dvec3 mode(0.0);
        for (int p = 0; p < 3; ++p) {
            double bpn = scratch.b[std::size_t(p) * (orders + 1) + n];
            if (plan.kind == SrbfTableKind::MarschnerColour)
                mode += row.fourier[p][std::size_t(n)] * bpn;
            else
                mode[p] = row.fourier[p][std::size_t(n)].x * bpn;
        }
        scratch.modes[std::size_t(n)] = mode;
    }
    for (int x = 0; x < plan.W; ++x) {
        glm::dvec3 value(0.0);
        const double* c = &plan.cosines[std::size_t(x) * (orders + 1)];
        for (int n = 0; n <= orders; ++n) value += scratch.modes[std::size_t(n)] * c[n];
        for (int channel = 0; channel < 3; ++channel)
            out[std::size_t(x) * plan.C + channel] = float(std::max(0.0, value[channel]));
    }
}

// Fills the texels of plane z = l·centres + k: 1/λ node l, θ_ξ node k.
void fillPlane(const TablePlan& plan, int z, PlaneScratch& scratch, std::vector<float>& texels) {
    const SrbfTableResolution& r = plan.r;
    const int l = z / r.centres, k = z % r.centres;
    const double lambda = 1.0 / node(l, r.bandwidths, kInverseLambdaMin, kInverseLambdaMax);
    const double thetaXi = node(k, r.centres, -0.5 * kPi, 0.5 * kPi);
    weighInclinations(plan, lambda, thetaXi, scratch);
    for (int y = 0; y < plan.H; ++y) {
        const OutgoingRow& row = plan.rows[std::size_t(y)];
        sumLongitudinalModes(plan, row, scratch);
        float* out = &texels[(std::size_t(z) * plan.H + y) * plan.W * plan.C];
        if (plan.kind == SrbfTableKind::KajiyaKay) {
            out[0] = float(scratch.b[0]);
            out[1] = float(scratch.b[1]);
            continue;
        }
        writeMarschnerRow(plan, row, scratch, out);
    }
}

SrbfConvolutionTable buildTable(SrbfTableKind kind, const SrbfTableResolution& requested,
                                SrbfTablePrecision precision, const MarschnerParameters& marschner,
                                float shininess) {
    SrbfConvolutionTable table;
    table.kind = kind;
    table.resolution = sanitised(kind, requested);
    table.precision = precision;
    table.channels = kind == SrbfTableKind::KajiyaKay ? 2 : 3;
    const SrbfTableResolution& r = table.resolution;
    const int W = r.azimuths, H = r.outgoing, C = table.channels;
    table.texels.assign(std::size_t(W) * H * table.depth() * C, 0.0f);

    const Inclinations inclinations;
    const std::vector<OutgoingRow> rows = outgoingRows(kind, r, marschner, shininess, inclinations);
    const int orders = kind == SrbfTableKind::KajiyaKay ? 0 : kFourierOrders;
    const int groups = kind == SrbfTableKind::KajiyaKay ? 2 : 3;
    const TablePlan plan{kind, r, W, H, C, orders, groups, inclinations, rows, azimuthCosines(W, orders)};

    // One task per (1/λ slab, θ_ξ node): its texels are the z = l·centres + k plane.
    tbb::parallel_for(tbb::blocked_range<int>(0, table.depth()), [&](const tbb::blocked_range<int>& range) {
        PlaneScratch scratch(plan);
        for (int z = range.begin(); z != range.end(); ++z) fillPlane(plan, z, scratch, table.texels);
    });
    if (precision == SrbfTablePrecision::Half)
        for (float& texel : table.texels) texel = roundToHalf(texel);
    return table;
}

// GL's GL_LINEAR weights along one axis for a normalised coordinate s
// (OpenGL 4.6 §8.14.2), clamp to edge.
struct AxisWeights {
    int i0 = 0, i1 = 0;
    float weight = 0.0f;
};
AxisWeights linearWeights(float s, int size) {
    float u = s * float(size) - 0.5f;
    float base = std::floor(u);
    AxisWeights a;
    a.weight = u - base;
    a.i0 = std::clamp(int(base), 0, size - 1);
    a.i1 = std::clamp(int(base) + 1, 0, size - 1);
    return a;
}

// u ∈ [0, size − 1] for a value on an axis whose nodes span [low, high].
float nodeCoordinate(double value, double low, double high, int size) {
    double u = (value - low) / (high - low) * double(size - 1);
    return float(std::clamp(std::isfinite(u) ? u : 0.0, 0.0, double(size - 1)));
}

glm::vec3 fetchTrilinear(const SrbfConvolutionTable& table, float s, float t, float r) {
    const int W = table.width(), H = table.height(), D = table.depth(), C = table.channels;
    AxisWeights ax = linearWeights(s, W), ay = linearWeights(t, H), az = linearWeights(r, D);
    glm::vec3 result(0.0f);
    for (int c = 0; c < std::min(C, 3); ++c) {
        auto texel = [&](int x, int y, int z) { return table.texels[((std::size_t(z) * H + y) * W + x) * C + c]; };
        auto plane = [&](int z) {
            float top = texel(ax.i0, ay.i0, z) * (1.0f - ax.weight) + texel(ax.i1, ay.i0, z) * ax.weight;
            float bottom = texel(ax.i0, ay.i1, z) * (1.0f - ax.weight) + texel(ax.i1, ay.i1, z) * ax.weight;
            return top * (1.0f - ay.weight) + bottom * ay.weight;
        };
        result[c] = plane(az.i0) * (1.0f - az.weight) + plane(az.i1) * az.weight;
    }
    return result;
}

}  // namespace

bool SrbfTableResolution::operator==(const SrbfTableResolution& other) const {
    return azimuths == other.azimuths && outgoing == other.outgoing && centres == other.centres &&
           bandwidths == other.bandwidths;
}

SrbfTableResolution defaultSrbfTableResolution(SrbfTableKind kind) {
    SrbfTableResolution r;
    if (kind == SrbfTableKind::KajiyaKay) r.azimuths = 1;
    return r;
}

std::vector<std::uint16_t> SrbfConvolutionTable::halfTexels() const {
    std::vector<std::uint16_t> result(texels.size());
    for (std::size_t i = 0; i < texels.size(); ++i) result[i] = glm::packHalf1x16(texels[i]);
    return result;
}

std::size_t SrbfConvolutionTable::gpuBytes() const {
    return texels.size() * (precision == SrbfTablePrecision::Half ? 2u : 4u);
}

SrbfConvolutionTable buildSrbfMarschnerTable(const MarschnerParameters& parameters,
                                             const SrbfTableResolution& resolution, SrbfTablePrecision precision) {
    return buildTable(SrbfTableKind::MarschnerColour, resolution, precision, parameters, 1.0f);
}

SrbfConvolutionTable buildSrbfMarschnerLobeTable(const MarschnerParameters& parameters,
                                                 const SrbfTableResolution& resolution,
                                                 SrbfTablePrecision precision) {
    MarschnerParameters white = parameters;
    white.sigmaA = glm::vec3(0.0f);
    return buildTable(SrbfTableKind::MarschnerLobes, resolution, precision, white, 1.0f);
}

SrbfConvolutionTable buildSrbfKajiyaKayTable(float shininess, const SrbfTableResolution& resolution,
                                             SrbfTablePrecision precision) {
    return buildTable(SrbfTableKind::KajiyaKay, resolution, precision, MarschnerParameters(), shininess);
}

SrbfTableAngles srbfTableAngles(const glm::vec3& t, const glm::vec3& wo, const SrbfLobe& lobe) {
    // marschnerAngles with ωi = ξ: sin θ_i = t·ξ, sin θ_r = t·ωo, φ = the
    // angle between their projections on the normal plane (0 when either is 0).
    MarschnerAngles a = marschnerAngles(t, lobe.centre, wo);
    SrbfTableAngles angles;
    angles.thetaO = std::asin(a.sinThetaR);
    angles.thetaXi = std::asin(a.sinThetaI);
    angles.psi = a.phi;
    angles.bandwidth = lobe.bandwidth;
    return angles;
}

glm::vec3 sampleSrbfTable(const SrbfConvolutionTable& table, const SrbfTableAngles& angles) {
    const SrbfTableResolution& r = table.resolution;
    if (table.texels.size() != std::size_t(table.width()) * table.height() * table.depth() * table.channels ||
        table.texels.empty())
        return glm::vec3(0.0f);
    const float halfPi = float(0.5 * kPi);
    float uPsi = nodeCoordinate(angles.psi, 0.0, kPi, r.azimuths);
    float uO = nodeCoordinate(angles.thetaO, -halfPi, halfPi, r.outgoing);
    float uXi = nodeCoordinate(angles.thetaXi, -halfPi, halfPi, r.centres);
    double inverse = angles.bandwidth > 0.0f ? 1.0 / double(angles.bandwidth) : kInverseLambdaMax;
    float uLambda = nodeCoordinate(inverse, kInverseLambdaMin, kInverseLambdaMax, r.bandwidths);
    int l0 = std::min(int(std::floor(uLambda)), r.bandwidths - 1), l1 = std::min(l0 + 1, r.bandwidths - 1);
    float w = uLambda - float(l0);
    float s = (uPsi + 0.5f) / float(table.width()), t = (uO + 0.5f) / float(table.height());
    auto slab = [&](int l) {
        return fetchTrilinear(table, s, t, (float(l * r.centres) + uXi + 0.5f) / float(table.depth()));
    };
    return slab(l0) * (1.0f - w) + slab(l1) * w;
}

glm::vec3 evaluateSrbfMarschnerTable(const SrbfConvolutionTable& table, const glm::vec3& t, const glm::vec3& wo,
                                     const SrbfLobe& lobe) {
    return sampleSrbfTable(table, srbfTableAngles(t, wo, lobe));
}

KajiyaKayTerms evaluateSrbfKajiyaKayTable(const SrbfConvolutionTable& table, const glm::vec3& t, const glm::vec3& wo,
                                          const SrbfLobe& lobe, const KajiyaKayParameters& parameters) {
    glm::vec3 value = sampleSrbfTable(table, srbfTableAngles(t, wo, lobe));
    KajiyaKayTerms terms;
    terms.diffuse = parameters.diffuse * value.x;
    terms.specular = parameters.specular * value.y;
    return terms;
}

}  // namespace hdhair
