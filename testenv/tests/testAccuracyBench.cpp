// hdhair-bench --accuracy --quick as CI runs it (under a minute on the 2-core
// machine): it exits 0 only when its own checks pass (AccuracyChecks.h), and
// its files are read back here and checked again: every approximation and
// preset has its rows, the CSV and Markdown hold them, and each
// approximation's error falls toward the reference within the allowance.
// With --cycles, the comparison with Blender's Cycles is wired through.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "Commands.h"

#include "hdHair/image/ImageWriter.h"
#include "hdHair/bench/AccuracyChecks.h"
#include "hdHair/bench/AccuracyMatrix.h"

using namespace hdhair;
namespace fs = std::filesystem;

namespace {

std::string readText(const fs::path& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

}  // namespace

TEST(AccuracyBench, QuickRunWritesAWellFormedReportWhoseErrorsFallTowardTheReference) {
    const fs::path out = fs::temp_directory_path() / "hdhair-accuracy-quick";
    fs::remove_all(out);
    std::string output;
    const int status = testenv::runCommand(std::string(HDHAIR_BENCH) + " --accuracy --quick --out " +
                                               testenv::shellQuoted(out.string()) + " --stage " +
                                               testenv::shellQuoted(HDHAIR_SOURCE_DIR "/examples/wavy_strands.usda"),
                                           &output);
    ASSERT_EQ(status, 0) << output;
    const nlohmann::json report = nlohmann::json::parse(readText(out / "accuracy.json"));
    const std::vector<std::string> problems = accuracy::checkAccuracyReport(report);
    EXPECT_TRUE(problems.empty()) << problems.front();
    EXPECT_TRUE(report["checks"].empty());
    EXPECT_TRUE(report["quick"].get<bool>());

    size_t expectedRows = accuracy::presetSteps().size();
    for (const accuracy::Approximation& approximation : accuracy::accuracyMatrix(true))
        expectedRows += approximation.steps.size();
    EXPECT_EQ(report["rows"].size(), expectedRows);
    EXPECT_EQ(report["approximations"].size(), accuracy::accuracyMatrix(true).size());
    for (const auto& row : report["rows"]) {
        EXPECT_TRUE(row["passes"].contains("strands")) << row.dump();
        EXPECT_EQ(row["fallback"], "") << row.dump();  // nothing quietly replaced what was asked
    }
    EXPECT_FALSE(report["machine"]["gl"].get<std::string>().empty());

    const std::string csv = readText(out / "accuracy.csv");
    EXPECT_EQ(csv.rfind("stage,approximation,step,settings,default,frame_median_ms,", 0), 0u) << csv;
    EXPECT_EQ(size_t(std::count(csv.begin(), csv.end(), '\n')), expectedRows + 1);
    const std::string markdown = readText(out / "accuracy.md");
    EXPECT_NE(markdown.find("### wavy_strands"), std::string::npos) << markdown;
    EXPECT_NE(markdown.find("| preset | quality=reference |"), std::string::npos) << markdown;
    EXPECT_NE(markdown.find("| preset | on the front | time gap | error gap | within 10 % |"), std::string::npos);

    // --report writes the same tables again from the JSON.
    output.clear();
    const fs::path again = out / "again";
    ASSERT_EQ(testenv::runCommand(std::string(HDHAIR_BENCH) + " --report " +
                                      testenv::shellQuoted((out / "accuracy.json").string()) + " --out " +
                                      testenv::shellQuoted(again.string()),
                                  &output),
              0)
        << output;
    EXPECT_EQ(readText(again / "accuracy.md"), markdown);
    EXPECT_EQ(readText(again / "accuracy.csv"), csv);

    // The plots, where Debian's matplotlib is installed (scripts/debian-packages.txt).
    output.clear();
    if (testenv::runCommand("/usr/bin/python3 -c 'import matplotlib'", &output) == 0) {
        output.clear();
        ASSERT_EQ(testenv::runCommand("/usr/bin/python3 " HDHAIR_SOURCE_DIR "/scripts/accuracy-plots.py " +
                                          testenv::shellQuoted((out / "accuracy.json").string()) + " " +
                                          testenv::shellQuoted(out.string()),
                                      &output),
                  0)
            << output;
        EXPECT_GT(fs::file_size(out / "accuracy.png"), 10000u);
        EXPECT_GT(fs::file_size(out / "accuracy-wavy_strands.png"), 10000u);
    }
    fs::remove_all(out);
}

// --cycles: each stage path-traced by Blender's Cycles too (small and few
// samples here: what is checked is the plumbing, not the figures). Every row
// is compared with both Cycles frames, the noise floor is measured from the
// two seeds, and the frames are written beside the report.
TEST(AccuracyBench, QuickRunAgainstCyclesComparesEveryRowWithBothCyclesFrames) {
    const fs::path out = fs::temp_directory_path() / "hdhair-accuracy-cycles";
    fs::remove_all(out);
    std::string output;
    const int status = testenv::runCommand(
        std::string(HDHAIR_BENCH) + " --accuracy --quick --cycles --cyclesSamples 8 --cyclesBlock 4 --imageWidth 48 --out " +
            testenv::shellQuoted(out.string()) + " --stage " +
            testenv::shellQuoted(HDHAIR_SOURCE_DIR "/examples/wavy_strands.usda"),
        &output);
    ASSERT_EQ(status, 0) << output;
    const nlohmann::json report = nlohmann::json::parse(readText(out / "accuracy.json"));
    EXPECT_EQ(report["commonSettings"], nlohmann::json::array({"shadingModel=marschner"}));
    ASSERT_EQ(report["stages"].size(), 1u);
    const nlohmann::json& stage = report["stages"][0];
    ASSERT_TRUE(stage.contains("cycles")) << stage.dump();
    const nlohmann::json& cycles = stage["cycles"];
    EXPECT_EQ(cycles["samples"], 8);
    EXPECT_EQ(cycles["block"], 4);
    EXPECT_EQ(cycles["version"].get<std::string>().rfind("Blender ", 0), 0u) << cycles.dump();
    // Two seeds differ, and single scattering loses light.
    EXPECT_GT(cycles["noiseFloor"]["blockRmse"].get<double>(), 0.0);
    EXPECT_LT(cycles["noiseFloor"]["blockRmse"].get<double>(), cycles["pixelNoiseFloor"].get<double>());
    EXPECT_LT(cycles["singleAgainstFull"]["sumRatio"].get<double>(), 1.0);
    for (const char* frame : {"full", "full-seed1", "single"}) {
        EXPECT_GT(cycles["seconds"][frame]["render"].get<double>(), 0.0) << frame;
        const hdhair::Image image = hdhair::readImage((out / ("wavy_strands.cycles-" + std::string(frame) + ".exr")).string());
        EXPECT_EQ(image.width, stage["width"].get<int>()) << frame;
        EXPECT_EQ(image.height, stage["height"].get<int>()) << frame;
    }
    bool someRowOnTheFront = false;
    for (const auto& row : report["rows"]) {
        ASSERT_TRUE(row.contains("cycles")) << row.dump();
        for (const char* against : {"full", "single"}) {
            const double error = row["cycles"][against]["blockRmse"].get<double>();
            EXPECT_TRUE(std::isfinite(error) && error > 0.0) << row.dump();
        }
        // Compared with two different frames, not one twice.
        EXPECT_NE(row["cycles"]["full"]["sumRatio"], row["cycles"]["single"]["sumRatio"]) << row.dump();
        someRowOnTheFront = someRowOnTheFront || row["cyclesPareto"].get<bool>();
    }
    EXPECT_TRUE(someRowOnTheFront);
    for (const auto& preset : report["presets"]) EXPECT_TRUE(preset.contains("cycles")) << preset.dump();
    const std::string markdown = readText(out / "accuracy.md");
    EXPECT_NE(markdown.find("#### wavy_strands against Cycles"), std::string::npos) << markdown;
    EXPECT_NE(markdown.find("Span of error against Cycles along each ladder"), std::string::npos) << markdown;
    fs::remove_all(out);
}

TEST(AccuracyBench, BadArgumentsAreOneLineErrors) {
    // Each is exit status 2 and one line that names the argument.
    const std::pair<const char*, const char*> mistakes[] = {
        {" --quick", "--quick"},
        {" --accuracy --repetitions 0", "--repetitions"},
        {" --cycles", "--cycles"},
        {" --accuracy --cycles --cyclesBlock 0", "--cyclesBlock"},
        {" --accuracy --cyclesSamples 8", "--cyclesSamples"},
        {" --table shadow", "--table"},
        {" --imageWidth 0", "--imageWidth"},
        {" --accuracy --repetitons 2", "--repetitons"},
    };
    std::string output;
    for (const auto& [arguments, named] : mistakes) {
        output.clear();
        EXPECT_EQ(testenv::runCommand(std::string(HDHAIR_BENCH) + arguments, &output), 2) << arguments << ": " << output;
        EXPECT_EQ(output.rfind("hdhair-bench: error: ", 0), 0u) << arguments << ": " << output;
        EXPECT_NE(output.find(named), std::string::npos) << arguments << ": " << output;
        EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << arguments << ": " << output;
    }
    output.clear();
    EXPECT_EQ(testenv::runCommand(std::string(HDHAIR_BENCH) + " --accuracy --quick --stage /nonexistent.usda", &output), 1);
    EXPECT_EQ(output.rfind("hdhair-bench: error: ", 0), 0u) << output;
    EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;
}
