#include "hdHair/tools/AccuracyReport.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "hdHair/base/AtomicFile.h"

namespace hdhair::accuracy {

namespace {

double timeOf(const nlohmann::json& row) { return row["frame"]["medianMs"].get<double>(); }
double errorOf(const nlohmann::json& row) { return row["error"]["rmse"].get<double>(); }

bool dominates(const nlohmann::json& a, const nlohmann::json& b) {
    return timeOf(a) <= timeOf(b) && errorOf(a) <= errorOf(b) && (timeOf(a) < timeOf(b) || errorOf(a) < errorOf(b));
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
        std::vector<nlohmann::json*> mine;
        for (auto& row : rows) {
            if (row["stage"] != name) continue;
            row["pareto"] = false;
            if (!otherReference.count(row["approximation"].get<std::string>())) mine.push_back(&row);
        }
        for (nlohmann::json* row : mine) {
            bool dominated = false;
            for (const nlohmann::json* other : mine) dominated = dominated || dominates(*other, *row);
            (*row)["pareto"] = !dominated;
        }
        for (const nlohmann::json* row : mine) {
            if ((*row)["approximation"] != "preset") continue;
            const double time = timeOf(*row), error = errorOf(*row);
            // The fastest front row at least as exact, and the most exact front row at least as fast.
            double fastest = time, mostExact = error;
            for (const nlohmann::json* front : mine) {
                if (!(*front)["pareto"].get<bool>()) continue;
                if (errorOf(*front) <= error) fastest = std::min(fastest, timeOf(*front));
                if (timeOf(*front) <= time) mostExact = std::min(mostExact, errorOf(*front));
            }
            const double timeGap = time > 0.0 ? (time - fastest) / time : 0.0;
            const double errorGap = error > 0.0 ? (error - mostExact) / error : 0.0;
            report["presets"].push_back({{"stage", name},
                                         {"preset", (*row)["label"]},
                                         {"onFront", (*row)["pareto"]},
                                         {"timeGap", timeGap},
                                         {"errorGap", errorGap},
                                         {"nearFront", std::min(timeGap, errorGap) <= kPresetFrontAllowance}});
        }
    }
}

std::string accuracyMarkdown(const nlohmann::json& report) {
    std::string text;
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
                      "covered_pixels,path,pareto\n";
    for (const auto& row : report["rows"])
        csv += fmt::format("{},{},{},{},{},{:.3f},{:.4f},{:.6f},{:.6f},{:.6f},{},{},{}\n",
                           csvField(row["stage"]), csvField(row["approximation"]), csvField(row["label"]),
                           csvField(joinedSettings(row["settings"])), row["isDefault"].get<bool>() ? 1 : 0, timeOf(row),
                           row["frame"]["spread"].get<double>(), errorOf(row), row["error"]["max"].get<double>(),
                           row["error"]["displayShare"].get<double>(), row["error"]["coveredPixels"].get<size_t>(),
                           csvField(row["path"]), row["pareto"].get<bool>() ? 1 : 0);
    writeTextFileAtomically(folder + "/accuracy.csv", csv);
    writeTextFileAtomically(folder + "/accuracy.md", accuracyMarkdown(report));
}

}  // namespace hdhair::accuracy
