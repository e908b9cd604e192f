// The accuracy report's Pareto front and the checks CI runs on it
// (AccuracyReport.h, AccuracyChecks.h), on reports made by hand: each check
// must catch the defect it exists for.

#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hdHair/bench/AccuracyChecks.h"
#include "hdHair/bench/AccuracyReport.h"

using namespace hdhair::accuracy;

namespace {

nlohmann::json row(const std::string& approximation, const std::string& label, double milliseconds, double rmse,
                   bool isDefault = false) {
    return {{"stage", "s"},
            {"approximation", approximation},
            {"label", label},
            {"settings", nlohmann::json::array({label})},
            {"isDefault", isDefault},
            {"frame", {{"medianMs", milliseconds}, {"spread", 0.05}}},
            {"passes", {{"strands", {{"medianMs", milliseconds / 2}, {"spread", 0.1}}}}},
            {"error",
             {{"rmse", rmse}, {"max", 2 * rmse}, {"displayShare", 0.5}, {"coveredPixels", 100}, {"ownRmse", rmse},
              {"ownMax", 2 * rmse}}},
            {"path", "binSorted"}};
}

// One stage: sortBins falling 0.03 -> 0.02 -> 0.01, lightsPerPass flat, and
// the presets (reference exact, default on sortBins' default).
nlohmann::json goodReport() {
    nlohmann::json report;
    report["stages"] = {{{"name", "s"}, {"width", 64}, {"height", 64}}};
    report["approximations"] = {
        {{"name", "sortBins"}, {"trend", "falls"}, {"checkedBeyondDefault", true}, {"base", nlohmann::json::array()},
         {"steps", {"1 bins", "256 bins", "1024 bins"}}},
        {{"name", "lightsPerPass"}, {"trend", "flat"}, {"checkedBeyondDefault", true}, {"base", nlohmann::json::array()},
         {"steps", {"1 lights", "4 lights"}}}};
    report["rows"] = {row("sortBins", "1 bins", 10, 0.03), row("sortBins", "256 bins", 20, 0.02, true),
                      row("sortBins", "1024 bins", 40, 0.01), row("lightsPerPass", "1 lights", 25, 0.02),
                      row("lightsPerPass", "4 lights", 20, 0.0201, true), row("preset", "quality=preview", 9, 0.04),
                      row("preset", "quality=default", 20, 0.02, true), row("preset", "quality=high", 60, 0.008),
                      row("preset", "quality=reference", 400, 0.0)};
    markParetoFront(report);
    return report;
}

nlohmann::json& rowOf(nlohmann::json& report, const std::string& label) {
    for (auto& r : report["rows"])
        if (r["label"] == label) return r;
    throw std::logic_error("no row " + label);
}

}  // namespace

TEST(AccuracyReport, MarksTheParetoFrontAndHowFarEachPresetIsFromIt) {
    nlohmann::json report = goodReport();
    EXPECT_TRUE(rowOf(report, "1 bins")["pareto"]);
    EXPECT_TRUE(rowOf(report, "1024 bins")["pareto"]);
    EXPECT_FALSE(rowOf(report, "1 lights")["pareto"]);  // slower than 256 bins at the same error
    EXPECT_TRUE(rowOf(report, "quality=preview")["pareto"]);
    // high (60 ms, 0.008) is dominated by nothing: 1024 bins is faster but less exact.
    EXPECT_TRUE(rowOf(report, "quality=high")["pareto"]);
    ASSERT_EQ(report["presets"].size(), 4u);
    for (const auto& preset : report["presets"]) {
        EXPECT_TRUE(preset["nearFront"]) << preset.dump();
        if (preset["preset"] == "quality=default") {
            // 256 bins is the same point: equal rows do not dominate each other.
            EXPECT_TRUE(preset["onFront"]);
            EXPECT_DOUBLE_EQ(preset["timeGap"].get<double>(), 0.0);
        }
    }
    // A default at 30 ms and RMSE 0.025: 256 bins (20 ms, 0.02) is 1/3
    // faster and 1/5 more exact; on the front's staircase it would need to be
    // within 10 % in one of them.
    rowOf(report, "quality=default")["frame"]["medianMs"] = 30.0;
    rowOf(report, "quality=default")["error"]["rmse"] = 0.025;
    markParetoFront(report);
    for (const auto& preset : report["presets"])
        if (preset["preset"] == "quality=default") {
            EXPECT_FALSE(preset["onFront"]);
            EXPECT_NEAR(preset["timeGap"].get<double>(), 1.0 / 3.0, 1e-12);
            EXPECT_NEAR(preset["errorGap"].get<double>(), 0.2, 1e-12);
            EXPECT_FALSE(preset["nearFront"]);
        }
    // At the front's error (slower only) it lies on the staircase: 0 % in error.
    rowOf(report, "quality=default")["error"]["rmse"] = 0.02;
    markParetoFront(report);
    for (const auto& preset : report["presets"])
        if (preset["preset"] == "quality=default") {
            EXPECT_TRUE(preset["nearFront"]);
        }
    rowOf(report, "quality=default")["error"]["rmse"] = 0.025;
    markParetoFront(report);
    const std::string markdown = accuracyMarkdown(report);
    EXPECT_NE(markdown.find("### s (64x64)"), std::string::npos) << markdown;
    EXPECT_NE(markdown.find("| sortBins | **256 bins** | 20.0 ms ± 2 % | 0.67x | 0.02000 | 0.0400 | 0.02000 | 50.00 % | * |"),
              std::string::npos)
        << markdown;
    EXPECT_NE(markdown.find("| quality=default | no | 33 % | 20 % | no |"), std::string::npos) << markdown;
}

// A row over a base (say Marschner shading) is measured against another
// reference: however good it looks, it is not on this front.
TEST(AccuracyReport, RowsAgainstAnotherReferenceAreNotOnTheFront) {
    nlohmann::json report = goodReport();
    report["approximations"].push_back({{"name", "msaaSamples"}, {"trend", "falls"}, {"checkedBeyondDefault", true},
                                        {"base", {"transparency=opaque"}}, {"steps", {"4 samples"}}});
    report["rows"].push_back(row("msaaSamples", "4 samples", 1, 0.001));
    markParetoFront(report);
    EXPECT_FALSE(rowOf(report, "4 samples")["pareto"]);
    EXPECT_TRUE(rowOf(report, "1 bins")["pareto"]);
    EXPECT_TRUE(rowOf(report, "quality=preview")["pareto"]);
}

TEST(AccuracyChecks, AGoodReportPasses) {
    const std::vector<std::string> problems = checkAccuracyReport(goodReport());
    EXPECT_TRUE(problems.empty()) << problems.front();
}

TEST(AccuracyChecks, AnErrorThatRisesTowardTheReferenceFails) {
    nlohmann::json report = goodReport();
    rowOf(report, "1024 bins")["error"]["ownRmse"] = 0.0225;  // over 0.02 x 1.1 + 2e-4
    const std::vector<std::string> problems = checkAccuracyReport(report);
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_EQ(problems[0], "s: sortBins's error rises from 0.02000 at 256 bins to 0.02250 at 1024 bins, more than the "
                           "noise allowance");
    // Within the allowance it passes.
    rowOf(report, "1024 bins")["error"]["ownRmse"] = 0.0219;
    EXPECT_TRUE(checkAccuracyReport(report).empty());
}

TEST(AccuracyChecks, AFallingLadderThatDoesNotFallFails) {
    nlohmann::json report = goodReport();
    for (const char* label : {"1 bins", "256 bins", "1024 bins"}) rowOf(report, label)["error"]["ownRmse"] = 0.02;
    const std::vector<std::string> problems = checkAccuracyReport(report);
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_EQ(problems[0], "sortBins's error falls on no stage (s: 1 bins (0.02000) to 1024 bins (0.02000))");
    // Beyond the allowance of the first step it fails on its stage, wherever else it falls.
    rowOf(report, "1 bins")["error"]["ownRmse"] = 0.019;
    rowOf(report, "256 bins")["error"]["ownRmse"] = 0.0205;
    rowOf(report, "1024 bins")["error"]["ownRmse"] = 0.0222;
    const std::vector<std::string> rising = checkAccuracyReport(report);
    ASSERT_EQ(rising.size(), 1u);
    EXPECT_EQ(rising[0], "s: sortBins's error does not fall from 1 bins (0.01900) to 1024 bins (0.02220)");
}

// A ladder that does not move on one stage (strands that never overlap do
// not care about bins) passes with a note when it falls on another stage.
TEST(AccuracyChecks, ALadderThatActsOnlyOnSomeStagesPassesWithANote) {
    nlohmann::json report = goodReport();
    nlohmann::json second = report;
    for (auto& row : second["rows"]) {
        row["stage"] = "t";
        if (row["approximation"] == "sortBins") row["error"]["ownRmse"] = 0.02;
    }
    for (const auto& row : second["rows"]) report["rows"].push_back(row);
    nlohmann::json stage = report["stages"][0];
    stage["name"] = "t";
    report["stages"].push_back(stage);
    std::vector<std::string> notes;
    const std::vector<std::string> problems = checkAccuracyReport(report, &notes);
    EXPECT_TRUE(problems.empty()) << problems.front();
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_EQ(notes[0], "sortBins does not change the error on t: 1 bins (0.02000) to 1024 bins (0.02000)");
}

TEST(AccuracyChecks, AFlatLadderThatMovesFails) {
    nlohmann::json report = goodReport();
    rowOf(report, "4 lights")["error"]["ownRmse"] = 0.03;
    const std::vector<std::string> problems = checkAccuracyReport(report);
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_EQ(problems[0].rfind("s: lightsPerPass should not change the error, but 4 lights gives RMSE 0.03000", 0), 0u)
        << problems[0];
}

TEST(AccuracyChecks, ChecksStopAtTheDefaultWhereTheLadderSaysSo) {
    nlohmann::json report = goodReport();
    rowOf(report, "1024 bins")["error"]["ownRmse"] = 0.05;
    EXPECT_FALSE(checkAccuracyReport(report).empty());
    report["approximations"][0]["checkedBeyondDefault"] = false;
    EXPECT_TRUE(checkAccuracyReport(report).empty());
}

TEST(AccuracyChecks, MalformedReportsFail) {
    nlohmann::json report = goodReport();
    report["rows"].erase(2);  // 1024 bins
    std::vector<std::string> problems = checkAccuracyReport(report);
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_EQ(problems[0], "s: no row for sortBins 1024 bins");

    report = goodReport();
    rowOf(report, "1 bins").erase("passes");
    EXPECT_EQ(checkAccuracyReport(report).size(), 1u);
    report = goodReport();
    rowOf(report, "1 bins")["frame"]["medianMs"] = 0.0;
    EXPECT_EQ(checkAccuracyReport(report).size(), 1u);
    report = goodReport();
    rowOf(report, "1 bins")["error"]["displayShare"] = 1.5;
    EXPECT_EQ(checkAccuracyReport(report).size(), 1u);
    report = goodReport();
    rowOf(report, "quality=reference")["error"]["rmse"] = 0.001;
    problems = checkAccuracyReport(report);
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_EQ(problems[0].rfind("s: quality=reference differs from its own reference", 0), 0u) << problems[0];
    report = goodReport();
    report.erase("presets");
    EXPECT_EQ(checkAccuracyReport(report), std::vector<std::string>{"the report has no 'presets' list"});
}

// Against Cycles every row shares one yardstick: the second front is marked
// by the block error against full path tracing, over rows whatever their
// base, and the report ranks the approximations by the span of that error.
TEST(AccuracyReport, MarksAFrontAgainstCyclesAndRanksTheApproximations) {
    nlohmann::json report = goodReport();
    const std::vector<std::pair<std::string, double>> cyclesErrors = {
        {"1 bins", 0.30}, {"256 bins", 0.29}, {"1024 bins", 0.29}, {"1 lights", 0.10}, {"4 lights", 0.40},
        {"quality=preview", 0.50}, {"quality=default", 0.29}, {"quality=high", 0.28}, {"quality=reference", 0.28}};
    for (const auto& [label, error] : cyclesErrors)
        rowOf(report, label)["cycles"] = {{"full", {{"blockRmse", error}, {"sumRatio", 0.6}, {"largest", 1.0}}},
                                          {"single", {{"blockRmse", error / 2}, {"sumRatio", 1.2}, {"largest", 1.0}}}};
    report["stages"][0]["cycles"] = {
        {"version", "Blender 3.4.1"},
        {"samples", 256},
        {"block", 16},
        {"seconds",
         {{"full", {{"render", 20.0}}}, {"full-seed1", {{"render", 21.0}}}, {"single", {{"render", 9.0}}}}},
        {"noiseFloor", {{"blockRmse", 0.05}, {"sumRatio", 1.0}, {"largest", 0.1}}},
        {"pixelNoiseFloor", 0.7},
        {"singleAgainstFull", {{"blockRmse", 0.5}, {"sumRatio", 0.4}, {"largest", 0.6}}}};
    markParetoFront(report);
    // The own front is unchanged; against Cycles "1 lights" (25 ms, 0.10) is
    // the most exact row, and dominates everything slower.
    EXPECT_FALSE(rowOf(report, "1 lights")["pareto"]);
    EXPECT_TRUE(rowOf(report, "1 lights")["cyclesPareto"]);
    EXPECT_TRUE(rowOf(report, "1 bins")["cyclesPareto"]);
    EXPECT_FALSE(rowOf(report, "quality=high")["cyclesPareto"]);
    EXPECT_FALSE(rowOf(report, "quality=reference")["cyclesPareto"]);
    for (const auto& preset : report["presets"]) {
        ASSERT_TRUE(preset.contains("cycles")) << preset.dump();
        if (preset["preset"] == "quality=high") {
            EXPECT_FALSE(preset["cycles"]["onFront"].get<bool>());
            // "1 lights" is faster (25 ms against 60) and more exact.
            EXPECT_NEAR(preset["cycles"]["timeGap"].get<double>(), (60.0 - 25.0) / 60.0, 1e-9);
        }
    }
    const std::string markdown = accuracyMarkdown(report);
    EXPECT_NE(markdown.find("#### s against Cycles"), std::string::npos) << markdown;
    EXPECT_NE(markdown.find("seed 1 against seed 0: 0.050 | 1.00"), std::string::npos) << markdown;
    // lightsPerPass spans 0.10 to 0.40, sortBins 0.29 to 0.30.
    EXPECT_NE(markdown.find("largest first: lightsPerPass 0.300, sortBins 0.010."), std::string::npos) << markdown;
    EXPECT_NE(markdown.find("| lightsPerPass | 1 lights | 25.0 ms | 0.100 | 0.60 | 0.050 | 1.20 | * |"),
              std::string::npos)
        << markdown;
    // The summary over the stages: the default's errors, the closest rows,
    // Cycles' time over the default frame's (20 s over 20 ms), and the spans
    // ranked against single scattering (lightsPerPass 0.15, sortBins 0.005).
    EXPECT_EQ(markdown.rfind("### Against Cycles, every stage", 0), 0u) << markdown;
    // Every error is two cells (block error, ratio of sums): twelve columns in all.
    EXPECT_NE(markdown.find("| stage | noise floor | sum | missing light | sum | default vs full | sum | default vs single "
                            "| sum | closest to full | closest to single | Cycles / default |\n|---|---|---|---|---|---|---|"
                            "---|---|---|---|---|\n"),
              std::string::npos)
        << markdown;
    EXPECT_NE(markdown.find("| 0.050 | 1.00 | 0.500 | 0.40 | 0.290 | 0.60 | 0.145 | 1.20 | lightsPerPass 1 lights (0.100) "
                            "| lightsPerPass 1 lights (0.050) | 1000x |"),
              std::string::npos)
        << markdown;
    EXPECT_NE(markdown.find("| lightsPerPass | 0.150 | 0.300 |\n| sortBins | 0.005 | 0.010 |"), std::string::npos)
        << markdown;
    // Without Cycles there is no summary.
    EXPECT_EQ(accuracyMarkdown(goodReport()).find("Against Cycles"), std::string::npos);
}
