#include "hdHair/bench/AccuracyReport.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>
#include <tuple>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "hdHair/base/AtomicFile.h"

namespace hdhair::accuracy {

namespace {

using ErrorOf = double (*)(const nlohmann::json& row);

double timeOf(const nlohmann::json& row) { return row["frame"]["medianMs"].get<double>(); }
double errorOf(const nlohmann::json& row) { return row["error"]["rmse"].get<double>(); }
double cyclesErrorOf(const nlohmann::json& row) { return row["cycles"]["full"]["blockRmse"].get<double>(); }

// Marks each of `rows` `flag` when no other is at least as fast and at least
// as exact (by `error`) and better in one; returns each preset's distance
// from that front (markParetoFront), in the rows' order.
nlohmann::json markFront(const std::vector<nlohmann::json*>& rows, ErrorOf error, const char* flag) {
    auto dominates = [error](const nlohmann::json& a, const nlohmann::json& b) {
        return timeOf(a) <= timeOf(b) && error(a) <= error(b) && (timeOf(a) < timeOf(b) || error(a) < error(b));
    };
    for (nlohmann::json* row : rows) {
        bool dominated = false;
        for (const nlohmann::json* other : rows) dominated = dominated || dominates(*other, *row);
        (*row)[flag] = !dominated;
    }
    nlohmann::json presets = nlohmann::json::array();
    for (const nlohmann::json* row : rows) {
        if ((*row)["approximation"] != "preset") continue;
        const double time = timeOf(*row), rowError = error(*row);
        // The fastest front row at least as exact, and the most exact front row at least as fast.
        double fastest = time, mostExact = rowError;
        for (const nlohmann::json* front : rows) {
            if (!(*front)[flag].get<bool>()) continue;
            if (error(*front) <= rowError) fastest = std::min(fastest, timeOf(*front));
            if (timeOf(*front) <= time) mostExact = std::min(mostExact, error(*front));
        }
        const double timeGap = time > 0.0 ? (time - fastest) / time : 0.0;
        const double errorGap = rowError > 0.0 ? (rowError - mostExact) / rowError : 0.0;
        presets.push_back({
            {"preset", (*row)["label"]},
            {"onFront", (*row)[flag]},
            {"timeGap", timeGap},
            {"errorGap", errorGap},
            {"nearFront", std::min(timeGap, errorGap) <= kPresetFrontAllowance}});
    }
    return presets;
}

std::string csvField(const std::string& text) {
    if (text.find_first_of(",\"") == std::string::npos) return text;
    std::string quoted = "\"";
    for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

std::string joinedSettings(const nlohmann::json& settings) {
    std::string text;
    for (const auto& setting : settings) text += (text.empty() ? "" : " ") + setting.get<std::string>();
    return text;
}

std::string errorCell(const nlohmann::json& error) {
    return fmt::format("{:.3f} | {:.2f}", error["blockRmse"].get<double>(), error["sumRatio"].get<double>());
}

// A stage's rows against Cycles: the Cycles frames' noise floor and times,
// every row's block error against full path tracing and single scattering,
// the presets against that front, and each approximation's span of error
// against full path tracing (how much of it that approximation decides).
std::string cyclesMarkdown(const nlohmann::json& report, const nlohmann::json& stage) {
    const std::string name = stage["name"];
    const nlohmann::json& cycles = stage["cycles"];
    std::string text = fmt::format(
        "#### {} against Cycles\n\n{}, {} samples a pixel; errors over {}-pixel blocks (relative RMSE | ratio of "
        "sums). Full path tracing took {:.1f} s (seed 1: {:.1f} s), single scattering {:.1f} s (Cycles' render "
        "times). Noise floor, seed 1 against seed 0: {} (per pixel {:.3f}). Single scattering against full: {}.\n\n",
        name, cycles["version"].get<std::string>(), cycles["samples"].get<int>(), cycles["block"].get<int>(),
        cycles["seconds"]["full"]["render"].get<double>(), cycles["seconds"]["full-seed1"]["render"].get<double>(),
        cycles["seconds"]["single"]["render"].get<double>(), errorCell(cycles["noiseFloor"]),
        cycles["pixelNoiseFloor"].get<double>(), errorCell(cycles["singleAgainstFull"]));
    text += "| approximation | step | frame | vs Cycles full | sum | vs single scattering | sum | front |\n"
            "|---|---|---|---|---|---|---|---|\n";
    std::map<std::string, std::pair<double, double>> spans;  // approximation: least and largest error
    for (const auto& row : report["rows"]) {
        if (row["stage"] != name || !row.contains("cycles")) continue;
        const std::string approximation = row["approximation"];
        const double error = cyclesErrorOf(row);
        auto [span, added] = spans.try_emplace(approximation, error, error);
        span->second.first = std::min(span->second.first, error);
        span->second.second = std::max(span->second.second, error);
        text += fmt::format("| {} | {} | {:.1f} ms | {} | {} | {} |\n", approximation, row["label"].get<std::string>(),
                            timeOf(row), errorCell(row["cycles"]["full"]), errorCell(row["cycles"]["single"]),
                            row.value("cyclesPareto", false) ? "*" : "");
    }
    text += "\n| preset | on the front against Cycles | time gap | error gap |\n|---|---|---|---|\n";
    for (const auto& preset : report["presets"]) {
        if (preset["stage"] != name || !preset.contains("cycles")) continue;
        const nlohmann::json& gaps = preset["cycles"];
        text += fmt::format("| {} | {} | {:.0f} % | {:.0f} % |\n", preset["preset"].get<std::string>(),
                            gaps["onFront"].get<bool>() ? "yes" : "no", 100.0 * gaps["timeGap"].get<double>(),
                            100.0 * gaps["errorGap"].get<double>());
    }
    std::vector<std::pair<double, std::string>> ranked;
    for (const auto& [approximation, span] : spans)
        if (approximation != "preset") ranked.emplace_back(span.second - span.first, approximation);
    std::sort(ranked.rbegin(), ranked.rend());
    text += "\nSpan of error against Cycles along each ladder, largest first:";
    for (size_t i = 0; i < ranked.size(); ++i)
        text += fmt::format("{} {} {:.3f}", i ? "," : "", ranked[i].second, ranked[i].first);
    return text + ".\n\n";
}

// Every stage against Cycles in one table, then each approximation's span of
// error (largest minus least along its ladder) averaged over the stages,
// against full path tracing and against single scattering: which settings
// decide how close a frame comes to the path-traced one, and how much of the
// error is the light hdHair does not carry (Cycles' single scattering
// against its full frame).
std::string cyclesSummaryMarkdown(const nlohmann::json& report) {
    std::string text =
        "### Against Cycles, every stage\n\nErrors over blocks (relative RMSE | ratio of sums, hdHair over "
        "Cycles). *Missing light*: Cycles' single scattering against its full frame. *Closest*: the row of the "
        "matrix with the least error. *Cycles / default*: Cycles' full render time over the default frame's.\n\n"
        "| stage | noise floor | sum | missing light | sum | default vs full | sum | default vs single | sum | closest "
        "to full | closest to single | Cycles / default |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    struct Span {
        double leastFull = std::numeric_limits<double>::infinity(), mostFull = 0.0;
        double leastSingle = std::numeric_limits<double>::infinity(), mostSingle = 0.0;
    };
    std::map<std::string, std::pair<double, double>> spanSums;  // approximation: summed spans (full, single)
    std::map<std::string, int> spanStages;
    int stages = 0;
    for (const auto& stage : report["stages"]) {
        if (!stage.contains("cycles")) continue;
        ++stages;
        const std::string name = stage["name"];
        const nlohmann::json& cycles = stage["cycles"];
        const nlohmann::json* defaultRow = nullptr;
        const nlohmann::json *closestFull = nullptr, *closestSingle = nullptr;
        std::map<std::string, Span> spans;
        for (const auto& row : report["rows"]) {
            if (row["stage"] != name || !row.contains("cycles")) continue;
            const double full = row["cycles"]["full"]["blockRmse"].get<double>();
            const double single = row["cycles"]["single"]["blockRmse"].get<double>();
            if (row["approximation"] == "preset" && row["label"] == "quality=default") defaultRow = &row;
            if (!closestFull || full < (*closestFull)["cycles"]["full"]["blockRmse"].get<double>()) closestFull = &row;
            if (!closestSingle || single < (*closestSingle)["cycles"]["single"]["blockRmse"].get<double>())
                closestSingle = &row;
            if (row["approximation"] == "preset") continue;
            Span& span = spans[row["approximation"].get<std::string>()];
            span.leastFull = std::min(span.leastFull, full);
            span.mostFull = std::max(span.mostFull, full);
            span.leastSingle = std::min(span.leastSingle, single);
            span.mostSingle = std::max(span.mostSingle, single);
        }
        for (const auto& [approximation, span] : spans) {
            spanSums[approximation].first += span.mostFull - span.leastFull;
            spanSums[approximation].second += span.mostSingle - span.leastSingle;
            ++spanStages[approximation];
        }
        const auto rowName = [](const nlohmann::json* row, const char* against) {
            if (!row) return std::string("-");
            return fmt::format("{} {} ({:.3f})", (*row)["approximation"].get<std::string>(),
                               (*row)["label"].get<std::string>(),
                               (*row)["cycles"][against]["blockRmse"].get<double>());
        };
        const double defaultTime = defaultRow ? timeOf(*defaultRow) : 0.0;
        text += fmt::format("| {} ({}x{}) | {} | {} | {} | {} | {} | {} | {} |\n", name, stage["width"].get<int>(),
                            stage["height"].get<int>(), errorCell(cycles["noiseFloor"]),
                            errorCell(cycles["singleAgainstFull"]),
                            defaultRow ? errorCell((*defaultRow)["cycles"]["full"]) : std::string("-"),
                            defaultRow ? errorCell((*defaultRow)["cycles"]["single"]) : std::string("-"),
                            rowName(closestFull, "full"), rowName(closestSingle, "single"),
                            defaultTime > 0.0
                                ? fmt::format("{:.0f}x", 1000.0 * cycles["seconds"]["full"]["render"].get<double>() /
                                                             defaultTime)
                                : std::string("-"));
    }
    if (stages == 0) return "";
    std::vector<std::tuple<double, double, std::string>> ranked;
    for (const auto& [approximation, sums] : spanSums)
        ranked.emplace_back(sums.second / spanStages[approximation], sums.first / spanStages[approximation],
                            approximation);
    std::sort(ranked.rbegin(), ranked.rend());
    text += "\nEach approximation's span of error along its ladder (largest minus least), the mean over the stages, "
            "largest against single scattering first:\n\n| approximation | span against single scattering | span "
            "against full path tracing |\n|---|---|---|\n";
    for (const auto& [single, full, approximation] : ranked)
        text += fmt::format("| {} | {:.3f} | {:.3f} |\n", approximation, single, full);
    return text + "\n";
}

}  // namespace

void markParetoFront(nlohmann::json& report) {
    nlohmann::json& rows = report["rows"];
    report["presets"] = nlohmann::json::array();
    for (const auto& stage : report["stages"]) {
        const std::string name = stage["name"];
        // Rows over a base (Marschner shading, the opaque path) are measured
        // against their own reference: another yardstick, so not on this front.
        std::set<std::string> otherReference;
        for (const auto& approximation : report["approximations"])
            if (!approximation["base"].empty()) otherReference.insert(approximation["name"].get<std::string>());
        std::vector<nlohmann::json*> mine, all;
        for (auto& row : rows) {
            if (row["stage"] != name) continue;
            row["pareto"] = false;
            if (!otherReference.count(row["approximation"].get<std::string>())) mine.push_back(&row);
            if (row.contains("cycles")) all.push_back(&row);
        }
        const nlohmann::json own = markFront(mine, errorOf, "pareto");
        // Against Cycles every row has the same yardstick, whatever its base.
        const nlohmann::json cycles = markFront(all, cyclesErrorOf, "cyclesPareto");
        for (nlohmann::json entry : own) {
            entry["stage"] = name;
            for (const auto& gaps : cycles)
                if (gaps["preset"] == entry["preset"]) entry["cycles"] = gaps;
            report["presets"].push_back(entry);
        }
    }
}

std::string accuracyMarkdown(const nlohmann::json& report) {
    std::string text = cyclesSummaryMarkdown(report);
    for (const auto& stage : report["stages"]) {
        const std::string name = stage["name"];
        double defaultTime = 0.0;
        for (const auto& row : report["rows"])
            if (row["stage"] == name && row["approximation"] == "preset" && row["label"] == "quality=default")
                defaultTime = timeOf(row);
        text += fmt::format("### {} ({}x{})\n\n", name, stage["width"].get<int>(), stage["height"].get<int>());
        text += "| approximation | step | frame (median ± half the range) | vs default | RMSE | max | own RMSE | display "
                "share | Pareto |\n|---|---|---|---|---|---|---|---|---|\n";
        for (const auto& row : report["rows"]) {
            if (row["stage"] != name) continue;
            const bool isDefault = row["isDefault"].get<bool>() && row["approximation"] != "msaaSamples" &&
                                   row["approximation"] != "marschner:azimuthal";
            const std::string step = isDefault ? "**" + row["label"].get<std::string>() + "**" : row["label"].get<std::string>();
            text += fmt::format("| {} | {} | {:.1f} ms ± {:.0f} % | {:.2f}x | {:.5f} | {:.4f} | {:.5f} | {:.2f} % | {} |\n",
                                row["approximation"].get<std::string>(), step, timeOf(row),
                                50.0 * row["frame"]["spread"].get<double>(),
                                defaultTime > 0.0 ? timeOf(row) / defaultTime : 0.0, errorOf(row),
                                row["error"]["max"].get<double>(), row["error"]["ownRmse"].get<double>(),
                                100.0 * row["error"]["displayShare"].get<double>(),
                                row["pareto"].get<bool>() ? "*" : "");
        }
        text += "\n| preset | on the front | time gap | error gap | within 10 % |\n|---|---|---|---|---|\n";
        for (const auto& preset : report["presets"]) {
            if (preset["stage"] != name) continue;
            text += fmt::format("| {} | {} | {:.0f} % | {:.0f} % | {} |\n", preset["preset"].get<std::string>(),
                                preset["onFront"].get<bool>() ? "yes" : "no", 100.0 * preset["timeGap"].get<double>(),
                                100.0 * preset["errorGap"].get<double>(), preset["nearFront"].get<bool>() ? "yes" : "no");
        }
        text += "\n";
        if (stage.contains("cycles")) text += cyclesMarkdown(report, stage);
    }
    return text;
}

void writeAccuracyReport(const nlohmann::json& report, const std::string& folder) {
    std::error_code error;
    std::filesystem::create_directories(folder, error);
    if (error) throw std::runtime_error("cannot make '" + folder + "': " + error.message());
    for (const char* file : {"accuracy.json", "accuracy.csv", "accuracy.md"})
        if (std::string why = whyNotWritable(folder + "/" + file); !why.empty())
            throw std::runtime_error("cannot write '" + folder + "/" + file + "': " + why);
    writeTextFileAtomically(folder + "/accuracy.json", report.dump(2) + "\n");
    std::string csv = "stage,approximation,step,settings,default,frame_median_ms,frame_spread,rmse,max,display_share,"
                      "covered_pixels,path,pareto,cycles_full_block_rmse,cycles_full_sum_ratio,"
                      "cycles_single_block_rmse,cycles_single_sum_ratio,cycles_pareto\n";
    for (const auto& row : report["rows"]) {
        csv += fmt::format("{},{},{},{},{},{:.3f},{:.4f},{:.6f},{:.6f},{:.6f},{},{},{}",
                           csvField(row["stage"]), csvField(row["approximation"]), csvField(row["label"]),
                           csvField(joinedSettings(row["settings"])), row["isDefault"].get<bool>() ? 1 : 0, timeOf(row),
                           row["frame"]["spread"].get<double>(), errorOf(row), row["error"]["max"].get<double>(),
                           row["error"]["displayShare"].get<double>(), row["error"]["coveredPixels"].get<size_t>(),
                           csvField(row["path"]), row["pareto"].get<bool>() ? 1 : 0);
        if (row.contains("cycles"))
            csv += fmt::format(",{:.6f},{:.6f},{:.6f},{:.6f},{}\n", cyclesErrorOf(row),
                               row["cycles"]["full"]["sumRatio"].get<double>(),
                               row["cycles"]["single"]["blockRmse"].get<double>(),
                               row["cycles"]["single"]["sumRatio"].get<double>(), row.value("cyclesPareto", false) ? 1 : 0);
        else
            csv += ",,,,,\n";
    }
    writeTextFileAtomically(folder + "/accuracy.csv", csv);
    writeTextFileAtomically(folder + "/accuracy.md", accuracyMarkdown(report));
}

}  // namespace hdhair::accuracy
