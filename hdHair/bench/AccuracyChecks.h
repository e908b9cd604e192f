#pragma once
// What the CI run of hdhair-bench --accuracy --quick checks in its report
// (AccuracyReport.h): that it is well formed, and that each approximation's
// own error (its RMSE at the reference's samples per pixel, AccuracyBench.h)
// falls as its setting moves toward the reference.
//
// Noise allowance: a step toward the reference may raise the RMSE by at most
// kRelativeNoise of the previous step's plus kAbsoluteNoise. Frames are
// deterministic, but a finer setting can move a strand edge across a pixel
// centre the reference does not agree on either: a little aliasing noise on
// top of the trend (measured on the quick stage: under 5 %). Along a Falls
// ladder the last checked step must also be below the first. A Falls ladder
// that stays within the allowance of its first step on a stage does not act
// there (bins on strands that never overlap): that is a note, not a failure,
// as long as the ladder falls on some other stage of the run; one that falls
// on no stage fails (so the one-stage quick run fails any ladder that does
// not fall). Along a Flat ladder every step stays within the allowance of the
// first.

#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace hdhair::accuracy {

constexpr double kRelativeNoise = 0.10;
constexpr double kAbsoluteNoise = 2e-4;
// The reference preset's RMSE against the stage's reference image: the
// microradian light turn of every timed frame moves it by about 2e-5.
constexpr double kSameImage = 1e-4;

// One line per problem found; empty when the report passes. `notes`, when
// given, receives the ladders that do not act on a stage.
std::vector<std::string> checkAccuracyReport(const nlohmann::json& report, std::vector<std::string>* notes = nullptr);

}  // namespace hdhair::accuracy
