#include "hdHair/reference/CyclesStrands.h"

#include <algorithm>
#include <array>

#include <glm/common.hpp>
#include <glm/vec4.hpp>

#include "hdHair/curves/CatmullRomEvaluation.h"

namespace hdhair {
namespace {

// σ_a per control point for a Principled Hair prim whose absorption varies:
// the material's per-point parameters (Marschner), or each point's colour
// through the same inversion hdHair's Marschner path uses (Kajiya-Kay).
std::vector<glm::vec3> controlAbsorption(const PreparedCurves& prepared, const HairMaterial& material) {
    std::vector<glm::vec3> sigmaA(prepared.controlPoints.size());
    if (material.model == ShadingModel::Marschner) {
        const std::vector<glm::vec4> points = hairParameterPoints(material, prepared);
        for (size_t k = 0; k < sigmaA.size(); ++k) sigmaA[k] = glm::vec3(points[2 * k]);
    } else {
        for (size_t k = 0; k < sigmaA.size(); ++k)
            sigmaA[k] = marschnerSigmaAFromColor(prepared.controlPoints[k].color);
    }
    return sigmaA;
}

}  // namespace

CyclesStrands cyclesStrands(const PreparedCurves& prepared, const HairMaterial& material, int pointsPerSpan) {
    CyclesStrands strands;
    strands.path = prepared.path;
    strands.flat = material.model == ShadingModel::Flat;
    const int steps = std::max(pointsPerSpan, 1);
    std::vector<glm::vec3> sigmaA;
    if (!strands.flat) {
        MarschnerParameters marschner = material.marschner;
        if (material.model == ShadingModel::KajiyaKay) marschner = MarschnerParameters{};
        strands.hair = principledHairFrom(marschner);
        strands.absorptionPerPoint =
            material.model == ShadingModel::KajiyaKay ? prepared.colorAuthored : (material.varies & kAbsorptionVaries) != 0;
        if (material.model == ShadingModel::KajiyaKay && !prepared.colorAuthored)
            strands.hair.absorption = marschner.sigmaA;
        if (strands.absorptionPerPoint) sigmaA = controlAbsorption(prepared, material);
    }
    const size_t segments = prepared.segmentCount();
    const size_t keys = segments * size_t(steps) + segments;  // an upper bound
    strands.positions.reserve(3 * keys);
    strands.radii.reserve(keys);
    strands.colors.reserve(3 * keys);
    strands.opacities.reserve(keys);
    for (size_t s = 0; s < segments; ++s) {
        const bool firstOfCurve = s == 0 || prepared.segmentCurve[s] != prepared.segmentCurve[s - 1];
        if (firstOfCurve) strands.keysPerCurve.push_back(0);
        const StrandControlPoint* controls = prepared.spanControls(s);
        const size_t first = prepared.segmentFirstControl[s];
        for (int step = firstOfCurve ? 0 : 1; step <= steps; ++step) {
            const float u = float(step) / float(steps);
            const StrandControlPoint point = evaluate(controls, u);
            strands.positions.insert(strands.positions.end(), {point.position.x, point.position.y, point.position.z});
            strands.radii.push_back(0.5f * std::max(point.width, 0.0f));
            strands.colors.insert(strands.colors.end(), {point.color.r, point.color.g, point.color.b});
            strands.opacities.push_back(std::clamp(point.opacity, 0.0f, 1.0f));
            if (strands.absorptionPerPoint) {
                const std::array<float, 4> w = catmullRomWeights(u);
                glm::vec3 value(0.0f);
                for (int i = 0; i < 4; ++i) value += w[size_t(i)] * sigmaA[first + size_t(i)];
                value = glm::max(value, glm::vec3(0.0f));
                strands.absorption.insert(strands.absorption.end(), {value.r, value.g, value.b});
            }
            ++strands.keysPerCurve.back();
        }
    }
    return strands;
}

}  // namespace hdhair
