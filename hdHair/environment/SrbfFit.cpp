#include "hdHair/environment/SrbfFit.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/vec3.hpp>

#include "hdHair/environment/NonNegativeLeastSquares.h"
#include "hdHair/environment/RadianceGridBlur.h"

namespace hdhair {

namespace {

// The bandwidths a lobe may take: 16 · 4^(k/8), k = 0..8, from
// kMinSrbfBandwidth to kMaxSrbfBandwidth in equal ratios (about 19 % apart,
// fine enough that the error barely depends on the step).
std::array<float, 9> candidateBandwidths() {
    std::array<float, 9> bandwidths{};
    for (size_t k = 0; k < bandwidths.size(); ++k)
        bandwidths[k] = kMinSrbfBandwidth * std::pow(kMaxSrbfBandwidth / kMinSrbfBandwidth, float(k) / 8.0f);
    bandwidths.back() = kMaxSrbfBandwidth;
    return bandwidths;
}

double sumOf(const glm::dvec3& v) { return v.x + v.y + v.z; }

// The fit in progress: the lobes, each one's kernel on every cell, and the
// residual radiance r_s = L_s − F_s.
class Fitter {
public:
    explicit Fitter(const RadianceGrid& grid)
        : grid_(grid), residual_(grid.cellCount()),
          candidateSpacing_(std::cos(kCandidateSpacingCells * glm::pi<float>() / float(grid.height))) {
        for (size_t s = 0; s < grid.cellCount(); ++s) {
            residual_[s] = glm::dvec3(grid.radiance[s]);
            energy_ += grid.solidAngles[s] * glm::dot(residual_[s], residual_[s]);
            mapPower_ += double(grid.solidAngles[s]) * residual_[s];
        }
    }

    double energy() const { return energy_; }
    size_t lobeCount() const { return lobes_.size(); }

    double relativeError() const {
        double error = 0.0;
        for (size_t s = 0; s < grid_.cellCount(); ++s) error += grid_.solidAngles[s] * glm::dot(residual_[s], residual_[s]);
        return energy_ > 0.0 ? std::sqrt(error / energy_) : 0.0;
    }

    // Adds a lobe where the most radiance is missing; false when nothing is.
    // The candidates are the kInsertionCandidates most under-lit cells at
    // least kCandidateSpacing apart, and the one whose lobe removes the most
    // residual energy wins: where the residual is what no lobe can remove
    // (already fitted as well as lobes can), a lobe would gain nothing.
    bool insert() {
        std::vector<size_t> order;
        for (size_t s = 0; s < grid_.cellCount(); ++s)
            if (sumOf(residual_[s]) > 0.0) order.push_back(s);
        std::stable_sort(order.begin(), order.end(),
                         [&](size_t a, size_t b) { return sumOf(residual_[a]) > sumOf(residual_[b]); });
        std::vector<size_t> candidates;
        for (size_t s : order) {
            bool apart = true;
            for (size_t c : candidates) apart = apart && glm::dot(grid_.directions[s], grid_.directions[c]) < candidateSpacing_;
            if (apart) candidates.push_back(s);
            if (candidates.size() == kInsertionCandidates) break;
        }
        Candidate best;
        for (size_t s : candidates) {
            Candidate candidate = bestBandwidth(grid_.directions[s], residual_);
            if (candidate.reduction > best.reduction) best = std::move(candidate);
        }
        if (!(best.reduction > 1e-12 * energy_)) return false;
        // Cells are 5.6° apart: a mean-shift step moves the lobe from the
        // cell's centre to the centre of the light it is to cover.
        if (Candidate shifted = bestBandwidth(meanShift(best.centre, best.kernel), residual_);
            shifted.reduction > best.reduction)
            best = std::move(shifted);
        lobes_.push_back(Srbf{SrbfLobe{best.centre, best.bandwidth}, glm::vec3(0.0f)});
        kernels_.push_back(std::move(best.kernel));
        gram_.emplace_back();
        projections_.emplace_back();
        updateProducts(lobes_.size() - 1);
        solveAmplitudes();
        return true;
    }

    // One coordinate-descent sweep over every lobe's centre and bandwidth.
    void refine() {
        for (size_t i = 0; i < lobes_.size(); ++i) {
            // The residual without lobe i.
            const glm::dvec3 amplitude(lobes_[i].amplitude);
            for (size_t s = 0; s < grid_.cellCount(); ++s) residual_[s] += amplitude * kernels_[i][s];
            Candidate best = bestBandwidth(lobes_[i].lobe.centre, residual_);
            const glm::vec3 shifted = meanShift(lobes_[i].lobe.centre, kernels_[i]);
            if (shifted != lobes_[i].lobe.centre) {
                Candidate moved = bestBandwidth(shifted, residual_);
                if (moved.reduction > best.reduction) best = std::move(moved);
            }
            lobes_[i].lobe.centre = best.centre;
            lobes_[i].lobe.bandwidth = best.bandwidth;
            lobes_[i].amplitude = glm::vec3(best.amplitude);
            kernels_[i] = std::move(best.kernel);
            updateProducts(i);
            for (size_t s = 0; s < grid_.cellCount(); ++s) residual_[s] -= best.amplitude * kernels_[i][s];
        }
        solveAmplitudes();
    }

    // The lobes with some amplitude, strongest (largest RGB sum) first.
    std::vector<Srbf> result() const {
        std::vector<Srbf> lobes;
        for (const Srbf& lobe : lobes_)
            if (lobe.amplitude.r > 0.0f || lobe.amplitude.g > 0.0f || lobe.amplitude.b > 0.0f) lobes.push_back(lobe);
        std::stable_sort(lobes.begin(), lobes.end(), [](const Srbf& a, const Srbf& b) {
            return a.amplitude.r + a.amplitude.g + a.amplitude.b > b.amplitude.r + b.amplitude.g + b.amplitude.b;
        });
        return lobes;
    }

private:
    struct Candidate {
        glm::vec3 centre{0.0f};
        float bandwidth = kMinSrbfBandwidth;
        glm::dvec3 amplitude{0.0};  // the best non-negative amplitude of this lobe alone
        double reduction = -1.0;    // the residual energy it removes
        std::vector<double> kernel;
    };

    std::vector<double> kernelAt(const glm::vec3& centre, float bandwidth) const {
        std::vector<double> kernel(grid_.cellCount());
        for (size_t s = 0; s < grid_.cellCount(); ++s) kernel[s] = srbfKernel(grid_.directions[s], centre, bandwidth);
        return kernel;
    }

    // The bandwidth whose lobe at `centre`, with its best non-negative
    // amplitude, removes the most of `residual`'s energy.
    Candidate bestBandwidth(const glm::vec3& centre, const std::vector<glm::dvec3>& residual) const {
        Candidate best;
        for (float bandwidth : kBandwidths) {
            Candidate candidate;
            candidate.centre = centre;
            candidate.bandwidth = bandwidth;
            candidate.kernel = kernelAt(centre, bandwidth);
            glm::dvec3 projection(0.0);
            double norm = 0.0;
            for (size_t s = 0; s < grid_.cellCount(); ++s) {
                const double weighted = grid_.solidAngles[s] * candidate.kernel[s];
                projection += weighted * residual[s];
                norm += weighted * candidate.kernel[s];
            }
            candidate.amplitude = glm::max(projection, glm::dvec3(0.0)) / norm;
            candidate.reduction = glm::dot(candidate.amplitude, projection);
            if (candidate.reduction > best.reduction) best = std::move(candidate);
        }
        return best;
    }

    // The residual-weighted mean direction under a lobe: where the light the
    // lobe should cover is centred.
    glm::vec3 meanShift(const glm::vec3& centre, const std::vector<double>& kernel) const {
        glm::dvec3 mean(0.0);
        for (size_t s = 0; s < grid_.cellCount(); ++s) {
            const double missing = std::max(0.0, sumOf(residual_[s]));
            mean += grid_.solidAngles[s] * kernel[s] * missing * glm::dvec3(grid_.directions[s]);
        }
        const double length = glm::length(mean);
        return length > 0.0 ? glm::vec3(mean / length) : centre;
    }

    // Lobe i's products with every lobe (its row and column of the Gram
    // matrix ⟨g_i, g_j⟩) and with the map (⟨g_i, L⟩ per channel), after lobe
    // i was added or changed: the rest of the matrix stays as it was.
    void updateProducts(size_t i) {
        const size_t n = lobes_.size();
        for (std::vector<double>& row : gram_) row.resize(n);
        for (size_t j = 0; j < n; ++j) {
            double sum = 0.0;
            for (size_t s = 0; s < grid_.cellCount(); ++s) sum += grid_.solidAngles[s] * kernels_[i][s] * kernels_[j][s];
            gram_[i][j] = gram_[j][i] = sum;
        }
        glm::dvec3 projection(0.0);
        for (size_t s = 0; s < grid_.cellCount(); ++s)
            projection += grid_.solidAngles[s] * kernels_[i][s] * glm::dvec3(grid_.radiance[s]);
        projections_[i] = projection;
    }

    // Every amplitude again, by NNLS per channel over all lobes, with the
    // map's power as one more equation, Σ_j a_j p_j = P (p_j = Σ_s ω_s g_j(s),
    // P = Σ_s ω_s L_s), weighted to hold all but exactly: least squares alone
    // leaves the residual orthogonal to each lobe, not to a constant, and
    // lobes no wider than λ = 16 leave gaps no non-negative amplitude fills,
    // so a smooth sky came out about 10 % short of its power. Hair's diffuse
    // response to a wide sky is close to an average over it: that shortfall
    // was the largest error of a lit strand against the reference
    // (testDomeReference: 0.90 of its brightness, relative RMSE 0.12; 0.02
    // with the power kept). Then the residual.
    void solveAmplitudes() {
        const size_t n = lobes_.size();
        std::vector<double> power(n, 0.0);
        double diagonal = 0.0, powerSquares = 0.0;
        for (size_t i = 0; i < n; ++i) {
            for (size_t s = 0; s < grid_.cellCount(); ++s) power[i] += grid_.solidAngles[s] * kernels_[i][s];
            diagonal += gram_[i][i];
            powerSquares += power[i] * power[i];
        }
        const double weight = powerSquares > 0.0 ? kPowerWeight * diagonal / powerSquares : 0.0;
        std::vector<double> gram(n * n);
        for (size_t i = 0; i < n; ++i)
            for (size_t j = 0; j < n; ++j) gram[i * n + j] = gram_[i][j] + weight * power[i] * power[j];
        for (int c = 0; c < 3; ++c) {
            std::vector<double> projections(n);
            for (size_t i = 0; i < n; ++i) projections[i] = projections_[i][c] + weight * power[i] * mapPower_[c];
            const std::vector<double> amplitudes = nonNegativeLeastSquares(gram, projections);
            for (size_t i = 0; i < n; ++i) lobes_[i].amplitude[c] = float(amplitudes[i]);
        }
        for (size_t s = 0; s < grid_.cellCount(); ++s) {
            residual_[s] = glm::dvec3(grid_.radiance[s]);
            for (size_t i = 0; i < n; ++i) residual_[s] -= glm::dvec3(lobes_[i].amplitude) * kernels_[i][s];
        }
    }

    inline static const std::array<float, 9> kBandwidths = candidateBandwidths();
    static constexpr size_t kInsertionCandidates = 8;
    // The power equation's weight against the Gram matrix (relative to the
    // mean of its diagonal over the mean p_j²): power kept to about 10⁻⁴.
    static constexpr double kPowerWeight = 1e4;
    static constexpr float kCandidateSpacingCells = 2.0f;  // in cell heights

    const RadianceGrid& grid_;
    std::vector<glm::dvec3> residual_;
    float candidateSpacing_;  // the cosine of the least angle between insertion candidates
    double energy_ = 0.0;
    glm::dvec3 mapPower_{0.0};  // P = Σ_s ω_s L_s per channel
    std::vector<Srbf> lobes_;
    std::vector<std::vector<double>> kernels_;    // each lobe's G on every cell
    std::vector<std::vector<double>> gram_;       // ⟨g_i, g_j⟩, solid-angle weighted
    std::vector<glm::dvec3> projections_;         // ⟨g_i, L⟩ per channel
};

}  // namespace

void checkSrbfFitSettings(const SrbfFitSettings& settings) {
    if (settings.maxLobes < 1 || settings.maxLobes > kMaxSrbfLobes)
        throw std::invalid_argument("SRBF fit: maxLobes must be between 1 and " + std::to_string(kMaxSrbfLobes));
    if (!(settings.targetError >= 0.0f) || settings.refinementSweeps < 0 || !(settings.prefilterBandwidth >= 0.0f))
        throw std::invalid_argument(
            "SRBF fit: targetError, refinementSweeps and prefilterBandwidth must not be negative");
}

SrbfFit fitSrbfs(const RadianceGrid& grid, const SrbfFitSettings& settings) {
    checkSrbfFitSettings(settings);
    const RadianceGrid target =
        settings.prefilterBandwidth > 0.0f ? blurredGrid(grid, settings.prefilterBandwidth) : grid;
    Fitter fitter(target);
    SrbfFit fit;
    if (!(fitter.energy() > 0.0)) return fit;  // a black map needs no lights
    while (int(fitter.lobeCount()) < settings.maxLobes && fitter.relativeError() > settings.targetError) {
        if (!fitter.insert()) break;
    }
    for (int sweep = 0; sweep < settings.refinementSweeps; ++sweep) fitter.refine();
    fit.srbfs = fitter.result();
    fit.relativeError = float(fitter.relativeError());
    return fit;
}

float srbfRelativeError(const RadianceGrid& grid, const std::vector<Srbf>& srbfs) {
    double error = 0.0, energy = 0.0;
    for (size_t s = 0; s < grid.cellCount(); ++s) {
        const glm::dvec3 radiance(grid.radiance[s]);
        const glm::dvec3 difference = radiance - glm::dvec3(srbfRadiance(srbfs, grid.directions[s]));
        error += grid.solidAngles[s] * glm::dot(difference, difference);
        energy += grid.solidAngles[s] * glm::dot(radiance, radiance);
    }
    return energy > 0.0 ? float(std::sqrt(error / energy)) : 0.0f;
}

}  // namespace hdhair
