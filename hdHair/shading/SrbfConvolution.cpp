#include "hdHair/shading/SrbfConvolution.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

namespace hdhair {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The fibre frame: t along the fibre, u towards ωo's azimuth, w = t × u.
struct FibreFrame {
    glm::dvec3 t, u, w;
    double sinThetaO = 0.0, cosThetaO = 1.0;
};

FibreFrame fibreFrame(const glm::vec3& tangent, const glm::vec3& wo) {
    FibreFrame frame;
    frame.t = glm::normalize(glm::dvec3(tangent));
    glm::dvec3 o = glm::normalize(glm::dvec3(wo));
    frame.sinThetaO = std::clamp(glm::dot(frame.t, o), -1.0, 1.0);
    frame.cosThetaO = std::sqrt(std::max(0.0, 1.0 - frame.sinThetaO * frame.sinThetaO));
    glm::dvec3 projected = o - frame.sinThetaO * frame.t;
    if (glm::length(projected) < 1e-9) {
        // ωo along t: any direction of the normal plane.
        glm::dvec3 other = std::abs(frame.t.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
        projected = other - glm::dot(other, frame.t) * frame.t;
    }
    frame.u = glm::normalize(projected);
    frame.w = glm::cross(frame.t, frame.u);
    return frame;
}

// The nodes of the product midpoint rule over the sphere in the fibre frame;
// a node's solid angle is weight · cos θ_i.
struct SphereNodes {
    std::vector<double> sinTheta, cosTheta, cosPhi, sinPhi, phi;
    double weight = 0.0;  // Δθ Δφ
};

SphereNodes sphereNodes(const SrbfQuadrature& quadrature) {
    SphereNodes nodes;
    int nTheta = std::max(2, quadrature.inclinations), nPhi = std::max(2, quadrature.azimuths);
    for (int k = 0; k < nTheta; ++k) {
        double theta = -0.5 * kPi + (k + 0.5) * kPi / nTheta;
        nodes.sinTheta.push_back(std::sin(theta));
        nodes.cosTheta.push_back(std::cos(theta));
    }
    for (int j = 0; j < nPhi; ++j) {
        double phi = -kPi + (j + 0.5) * 2.0 * kPi / nPhi;
        nodes.phi.push_back(phi);
        nodes.cosPhi.push_back(std::cos(phi));
        nodes.sinPhi.push_back(std::sin(phi));
    }
    nodes.weight = (kPi / nTheta) * (2.0 * kPi / nPhi);
    return nodes;
}

glm::dvec3 directionAt(const FibreFrame& frame, const SphereNodes& nodes, std::size_t k, std::size_t j) {
    return nodes.sinTheta[k] * frame.t + nodes.cosTheta[k] * (nodes.cosPhi[j] * frame.u + nodes.sinPhi[j] * frame.w);
}

}  // namespace

SrbfMarschnerResponse convolveSrbfMarschner(const glm::vec3& t, const glm::vec3& wo, const SrbfLobe& lobe,
                                            const MarschnerParameters& parameters,
                                            const SrbfQuadrature& quadrature) {
    const FibreFrame frame = fibreFrame(t, wo);
    const SphereNodes nodes = sphereNodes(quadrature);
    const glm::dvec3 xi = glm::normalize(glm::dvec3(lobe.centre));
    const double lambda = lobe.bandwidth;
    // f = Σ_p M_p(θ_i, θ_r) N_p(|φ|, cos θ_r) (Marschner.h: N_p is evaluated
    // at θ_r, so it depends on φ_i only): N_p once per azimuth node.
    const float cosThetaO = float(frame.cosThetaO), sinThetaO = float(frame.sinThetaO);
    std::vector<glm::dvec3> azimuthal[3];
    for (int p = 0; p < 3; ++p)
        for (double phi : nodes.phi)
            azimuthal[p].push_back(glm::dvec3(marschnerAzimuthal(p, float(std::abs(phi)), cosThetaO, parameters)));
    const double xiT = glm::dot(xi, frame.t), xiU = glm::dot(xi, frame.u), xiW = glm::dot(xi, frame.w);
    glm::dvec3 lobes[3] = {glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.0)};
    for (std::size_t k = 0; k < nodes.sinTheta.size(); ++k) {
        glm::dvec3 sums[3] = {glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.0)};
        for (std::size_t j = 0; j < nodes.phi.size(); ++j) {
            double cosine = nodes.sinTheta[k] * xiT + nodes.cosTheta[k] * (nodes.cosPhi[j] * xiU + nodes.sinPhi[j] * xiW);
            double g = std::exp(lambda * (cosine - 1.0));
            for (int p = 0; p < 3; ++p) sums[p] += g * azimuthal[p][j];
        }
        for (int p = 0; p < 3; ++p) {
            double m = marschnerLongitudinal(float(nodes.sinTheta[k]), float(nodes.cosTheta[k]), sinThetaO, cosThetaO,
                                             parameters.alpha[p], marschnerLongitudinalVariance(parameters.beta[p]));
            lobes[p] += (m * nodes.cosTheta[k]) * sums[p];
        }
    }
    SrbfMarschnerResponse response;
    response.R = glm::vec3(lobes[0] * nodes.weight);
    response.TT = glm::vec3(lobes[1] * nodes.weight);
    response.TRT = glm::vec3(lobes[2] * nodes.weight);
    return response;
}

KajiyaKayTerms convolveSrbfKajiyaKay(const glm::vec3& t, const glm::vec3& wo, const SrbfLobe& lobe,
                                     const KajiyaKayParameters& parameters, const SrbfQuadrature& quadrature) {
    const FibreFrame frame = fibreFrame(t, wo);
    const SphereNodes nodes = sphereNodes(quadrature);
    double diffuse = 0.0, specular = 0.0;
    for (std::size_t k = 0; k < nodes.sinTheta.size(); ++k)
        for (std::size_t j = 0; j < nodes.phi.size(); ++j) {
            glm::dvec3 wi = directionAt(frame, nodes, k, j);
            double g = srbfKernel(lobe, wi) * nodes.cosTheta[k];
            KajiyaKayTerms f = evaluateKajiyaKay(t, glm::vec3(wi), wo, parameters);
            diffuse += g * f.diffuse;
            specular += g * f.specular;
        }
    KajiyaKayTerms terms;
    terms.diffuse = float(diffuse * nodes.weight);
    terms.specular = float(specular * nodes.weight);
    return terms;
}

}  // namespace hdhair
