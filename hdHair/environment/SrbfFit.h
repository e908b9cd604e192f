#pragma once
// Fits Gaussian SRBF lights (Srbf.h) to an environment sampled on a grid
// (RadianceGrid.h): the approximation of Ren et al. 2010, §3 Eq. (2), fitted
// as their §7 describes in outline (greedy insertion at the largest error,
// λ bounded to [16, 64]), in a way fast enough to run when a stage loads
// instead of the paper's 5-20 minutes per map.
//
// Algorithm (deterministic: no random numbers, serial loops, ties to the
// lowest index):
// 1. Greedy insertion. The new lobe's centre ξ is the cell with the largest
//    residual L − F (summed over RGB: the most radiance still missing). Its
//    bandwidth λ is the one of nine, 16 · 4^(k/8) for k = 0..8, whose lobe
//    alone removes the most residual energy, Σ_c max(0, ⟨r_c, g⟩)² / ⟨g, g⟩.
//    Then every amplitude (RGB, each channel on its own) is solved again by
//    non-negative least squares over all lobes (NonNegativeLeastSquares.h):
//    negative lobes would subtract light and, once each lobe is shadowed
//    separately, could leave negative radiance (digest 002, §9.2). The map's
//    power is one more equation, Σ_j a_j p_j = Σ_s ω_s L_s (p_j the lobe's
//    integral over the grid), weighted to hold to about 10⁻⁴: without it a
//    smooth sky's fit fell about 10 % short of its power (the gaps between
//    lobes), the largest error of a lit strand against the reference.
// 2. Stop inserting at maxLobes lobes, or once the error is at most
//    targetError, or when no cell is under-lit any more.
// 3. Refinement sweeps (the paper refines centres and bandwidths with
//    Tsai and Shih's optimiser; this is a cheap coordinate descent instead):
//    each lobe in turn, holding the others, moves to the better of its
//    centre and the residual-weighted mean direction under it (a mean-shift
//    step), with the best of the nine bandwidths and its best non-negative
//    amplitude; then all amplitudes are solved again. Every step can only
//    lower the error; lobes left with zero amplitude are dropped.
//
// Error measure (returned as SrbfFit::relativeError): the relative L2 error
// over the sphere, every cell weighted by its solid angle ω_s and the three
// channels summed,
//   E = sqrt( Σ_s ω_s |L_s − F_s|² / Σ_s ω_s |L_s|² ),
// F_s the fitted radiance at the cell's centre and L_s the cell's mean
// radiance. E² is the paper's "mean squared error of the fitting" relative
// to the map's energy; the paper stops below 15 % (E ≈ 0.39).
//
// E is measured against the map after the prefilter (RadianceGridBlur.h):
// what a fit within the paper's bandwidths could reach.
//
// How well the fit does on a uniform map and a sky, with 30 and 60 lobes,
// and what it costs: hdHair/environment/README.md has the table
// (testSrbfFit pins the errors; hdhair-bench SrbfFit/1024x512 the time).
// Lobes no wider than λ = 16 ripple over a constant, so a uniform map is
// the hardest case for its energy.

#include <vector>

#include "hdHair/environment/RadianceGrid.h"
#include "hdHair/environment/Srbf.h"

namespace hdhair {

struct SrbfFitSettings {
    // The paper starts from 30 SRBFs and ends with 30-60 (§7); a fixed
    // count keeps the lighting's cost predictable. 1..kMaxSrbfLobes.
    int maxLobes = 30;
    // Stop inserting once E is at most this (0: always maxLobes lobes).
    float targetError = 0.0f;
    // Coordinate-descent sweeps over centres and bandwidths after insertion.
    int refinementSweeps = 2;
    // The bandwidth of the blur applied before fitting (RadianceGridBlur.h);
    // 0: none. The narrowest lobe's, so that a sun keeps its power.
    float prefilterBandwidth = kMaxSrbfBandwidth;

    bool operator==(const SrbfFitSettings& other) const {
        return maxLobes == other.maxLobes && targetError == other.targetError &&
               refinementSweeps == other.refinementSweeps && prefilterBandwidth == other.prefilterBandwidth;
    }
};

constexpr int kMaxSrbfLobes = 256;

struct SrbfFit {
    std::vector<Srbf> srbfs;     // in the grid's frame (the dome's), strongest first
    float relativeError = 0.0f;  // E above; 0 for a black map
};

// Throws std::invalid_argument naming the setting when one is out of range.
void checkSrbfFitSettings(const SrbfFitSettings& settings);

// Throws std::invalid_argument for settings out of range.
SrbfFit fitSrbfs(const RadianceGrid& grid, const SrbfFitSettings& settings = {});

// E of `srbfs` against `grid`: the measure above, for any set of lobes.
float srbfRelativeError(const RadianceGrid& grid, const std::vector<Srbf>& srbfs);

}  // namespace hdhair
