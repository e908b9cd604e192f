#include "hdHair/bench/AccuracyChecks.h"

#include <cmath>
#include <map>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace hdhair::accuracy {

namespace {

bool isNumber(const nlohmann::json& json, const char* key) {
    return json.contains(key) && json[key].is_number() && std::isfinite(json[key].get<double>());
}

// The row's shape: names, settings, timings and errors present and sane.
void checkRow(const nlohmann::json& row, std::vector<std::string>& problems) {
    const std::string where = fmt::format("row {}", row.dump().substr(0, 80));
    for (const char* key : {"stage", "approximation", "label", "path"})
        if (!row.contains(key) || !row[key].is_string()) problems.push_back(where + ": no '" + key + "'");
    if (!row.contains("settings") || !row["settings"].is_array()) problems.push_back(where + ": no settings list");
    if (!row.contains("pareto") || !row["pareto"].is_boolean()) problems.push_back(where + ": no Pareto mark");
    if (!row.contains("frame") || !isNumber(row["frame"], "medianMs") || row["frame"]["medianMs"].get<double>() <= 0.0 ||
        !isNumber(row["frame"], "spread") || row["frame"]["spread"].get<double>() < 0.0)
        problems.push_back(where + ": no positive frame median and spread");
    if (!row.contains("passes") || !row["passes"].is_object() || row["passes"].empty())
        problems.push_back(where + ": no pass timings");
    else
        for (const auto& [name, pass] : row["passes"].items())
            if (!isNumber(pass, "medianMs") || !isNumber(pass, "spread"))
                problems.push_back(where + ": pass '" + name + "' has no median and spread");
    if (!row.contains("error")) {
        problems.push_back(where + ": no error");
        return;
    }
    const nlohmann::json& error = row["error"];
    for (const char* key : {"rmse", "max", "displayShare", "ownRmse", "ownMax"})
        if (!isNumber(error, key) || error[key].get<double>() < 0.0)
            problems.push_back(where + ": error '" + key + "' is not a number >= 0");
    if (isNumber(error, "displayShare") && error["displayShare"].get<double>() > 1.0)
        problems.push_back(where + ": display share over 1");
    if (!isNumber(error, "coveredPixels") || error["coveredPixels"].get<double>() <= 0.0)
        problems.push_back(where + ": no covered pixels");
}

// Falls ladders that fell on some stage, and those that stayed within the
// noise allowance of their first step, stage by stage.
struct LadderTrends {
    std::map<std::string, bool> fallsSomewhere;
    std::map<std::string, std::vector<std::string>> stillOn;
};

// The row of one step on one stage; null when the report has none.
const nlohmann::json* findRow(const nlohmann::json& report, const std::string& stage, const std::string& approximation,
                              const std::string& label) {
    for (const auto& row : report["rows"])
        if (row["stage"] == stage && row["approximation"] == approximation && row["label"] == label) return &row;
    return nullptr;
}

void checkPresets(const nlohmann::json& report, const std::string& name, std::vector<std::string>& problems) {
    for (const char* preset : {"quality=preview", "quality=default", "quality=high", "quality=reference"}) {
        const nlohmann::json* row = findRow(report, name, "preset", preset);
        if (!row) {
            problems.push_back(fmt::format("{}: no row for {}", name, preset));
            continue;
        }
        // The reference compared with itself: rendering is deterministic,
        // but every frame turns the lights by a microradian (BenchLights.h).
        if (std::string(preset) == "quality=reference" && (*row)["error"]["rmse"].get<double>() > kSameImage)
            problems.push_back(fmt::format("{}: quality=reference differs from its own reference (RMSE {})", name,
                                           (*row)["error"]["rmse"].get<double>()));
    }
}

// The own RMSE of each of a ladder's steps on one stage, and (defaultStep)
// where the default's is among them; a step with no row is a problem, and
// left out.
std::vector<double> ladderErrors(const nlohmann::json& report, const std::string& name,
                                 const std::string& approximationName, const nlohmann::json& steps, size_t& defaultStep,
                                 std::vector<std::string>& problems) {
    std::vector<double> errors;
    for (const auto& step : steps) {
        const nlohmann::json* row = findRow(report, name, approximationName, step);
        if (!row) {
            problems.push_back(fmt::format("{}: no row for {} {}", name, approximationName, step.get<std::string>()));
            continue;
        }
        if ((*row)["isDefault"].get<bool>()) defaultStep = errors.size();
        errors.push_back((*row)["error"]["ownRmse"].get<double>());
    }
    return errors;
}

void checkFlatLadder(const std::string& name, const std::string& approximationName, const nlohmann::json& steps,
                     const std::vector<double>& errors, std::vector<std::string>& problems) {
    for (size_t i = 1; i < errors.size(); ++i)
        if (std::abs(errors[i] - errors[0]) > kRelativeNoise * errors[0] + kAbsoluteNoise)
            problems.push_back(
                fmt::format("{}: {} should not change the error, but {} gives RMSE {:.5f} "
                            "against {:.5f} at {}",
                            name, approximationName, steps[i].get<std::string>(), errors[i], errors[0],
                            steps[0].get<std::string>()));
}

// Each step up to `last` within the noise allowance of the one before, and
// the error at `last` below the first step's (noted in `trends` when it
// only stays put).
void checkFallingLadder(const std::string& name, const std::string& approximationName, const nlohmann::json& steps,
                        const std::vector<double>& errors, size_t last, LadderTrends& trends,
                        std::vector<std::string>& problems) {
    for (size_t i = 1; i <= last; ++i)
        if (errors[i] > errors[i - 1] * (1.0 + kRelativeNoise) + kAbsoluteNoise)
            problems.push_back(
                fmt::format("{}: {}'s error rises from {:.5f} at {} to {:.5f} at {}, more than "
                            "the noise allowance",
                            name, approximationName, errors[i - 1], steps[i - 1].get<std::string>(), errors[i],
                            steps[i].get<std::string>()));
    if (last == 0) return;
    const std::string ends = fmt::format("{} ({:.5f}) to {} ({:.5f})", steps[0].get<std::string>(), errors[0],
                                         steps[last].get<std::string>(), errors[last]);
    if (errors[last] < errors[0])
        trends.fallsSomewhere[approximationName] = true;
    else if (errors[last] - errors[0] <= kRelativeNoise * errors[0] + kAbsoluteNoise)
        trends.stillOn[approximationName].push_back(fmt::format("{}: {}", name, ends));
    else
        problems.push_back(fmt::format("{}: {}'s error does not fall from {}", name, approximationName, ends));
}

void checkLadder(const nlohmann::json& report, const std::string& name, const nlohmann::json& approximation,
                 LadderTrends& trends, std::vector<std::string>& problems) {
    const std::string approximationName = approximation["name"];
    size_t defaultStep = 0;
    const std::vector<double> errors =
        ladderErrors(report, name, approximationName, approximation["steps"], defaultStep, problems);
    if (errors.size() != approximation["steps"].size() || errors.size() < 2) return;
    const auto& steps = approximation["steps"];
    if (approximation["trend"] == "flat") {
        checkFlatLadder(name, approximationName, steps, errors, problems);
        return;
    }
    const size_t last = approximation["checkedBeyondDefault"].get<bool>() ? errors.size() - 1 : defaultStep;
    checkFallingLadder(name, approximationName, steps, errors, last, trends, problems);
}

// A ladder that stays put on a stage, within the allowance, is an
// approximation that does not act there (bins on strands that do not
// overlap, shadow layers on strands that do not shadow themselves). It
// must still act somewhere: one that falls on no stage of the run is
// ignored, or broken, everywhere.
void checkLaddersActSomewhere(const LadderTrends& trends, std::vector<std::string>& problems,
                              std::vector<std::string>* notes) {
    for (const auto& [approximationName, stages] : trends.stillOn) {
        if (trends.fallsSomewhere.count(approximationName)) {
            for (const std::string& stage : stages)
                if (notes) notes->push_back(fmt::format("{} does not change the error on {}", approximationName, stage));
            continue;
        }
        std::string where;
        for (const std::string& stage : stages) where += (where.empty() ? "" : "; ") + stage;
        problems.push_back(fmt::format("{}'s error falls on no stage ({})", approximationName, where));
    }
}

}  // namespace

std::vector<std::string> checkAccuracyReport(const nlohmann::json& report, std::vector<std::string>* notes) {
    std::vector<std::string> problems;
    LadderTrends trends;
    for (const char* key : {"stages", "approximations", "rows", "presets"})
        if (!report.contains(key) || !report[key].is_array() || report[key].empty())
            problems.push_back(std::string("the report has no '") + key + "' list");
    if (!problems.empty()) return problems;
    for (const auto& row : report["rows"]) checkRow(row, problems);
    if (!problems.empty()) return problems;

    for (const auto& stage : report["stages"]) {
        const std::string name = stage.value("name", "");
        checkPresets(report, name, problems);
        for (const auto& approximation : report["approximations"])
            checkLadder(report, name, approximation, trends, problems);
    }
    checkLaddersActSomewhere(trends, problems, notes);
    return problems;
}

}  // namespace hdhair::accuracy
