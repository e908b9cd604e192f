#pragma once
// The report of hdhair-bench --accuracy (AccuracyBench.h): each stage's
// error-versus-time Pareto front marked on its rows, how close each quality
// preset lies to it, and the files: accuracy.json (everything),
// accuracy.csv (one line a row) and accuracy.md (the tables docs/accuracy.md
// shows). scripts/accuracy-plots.py draws the plots from the JSON.

#include <string>

#include <nlohmann/json_fwd.hpp>

namespace hdhair::accuracy {

// How far a preset may lie from the front, in time or in error.
constexpr double kPresetFrontAllowance = 0.10;

// Marks every row "pareto": true when no other row of its stage is at least
// as fast and at least as exact (median frame time, RMSE) and better in one
// (rows over a base, measured against another reference, are never on it),
// and adds "presets": per stage and preset, "onFront", and "timeGap" and
// "errorGap": how much faster, or more exact, the best front row that is
// also at least as good in the other measure is, relative to the preset
// (0 on the front); "nearFront" when either is within kPresetFrontAllowance.
void markParetoFront(nlohmann::json& report);

// Writes accuracy.json, accuracy.csv and accuracy.md into `folder` (made
// when missing). Throws std::runtime_error naming a file it cannot write.
void writeAccuracyReport(const nlohmann::json& report, const std::string& folder);

// The Markdown tables: per stage, a row per measurement (approximation,
// step, frame time as median and half its range and relative to the
// default, RMSE, max, own RMSE, display share, Pareto), then the presets
// against the front; for a stage compared with Cycles, the same rows against
// Cycles (full and single scattering) with the noise floor and Cycles'
// times, the presets against that front, and the approximations ranked by
// how far their error against Cycles moves along their ladders.
std::string accuracyMarkdown(const nlohmann::json& report);

}  // namespace hdhair::accuracy
