// Built and run only with OpenUSD. The testenv cases whose arguments are all
// usdrecord's (TestCase::usdrecordCompatible: a camera, complexity, width,
// purposes; no hdHair-only settings) rendered once more, through
// `usdrecord --renderer HdHair --disableGpu`, and compared with the same
// baselines through the same display transform and thresholds: the plugin
// must draw what hdhair-record draws from the same stage.
//
// usdrecord's --disableGpu path writes the colour AOV as it is: scene-linear
// in the rendering space (lin_rec709: these cases set no renderingSpace),
// pre-multiplied, with no colour-space metadata. The test tags the EXR with
// that space, which is what a case's display transform starts from.

#include <filesystem>
#include <iostream>
#include <string>

#include <gtest/gtest.h>

#include "Commands.h"
#include "StageRendering.h"
#include "TestCases.h"
#include "hdHair/image/ImageWriter.h"

using namespace hdhair;
using namespace hdhair::testenv;
namespace fs = std::filesystem;

namespace {

// The case's hdhair-record arguments as usdrecord spells them.
std::string usdrecordArguments(const TestCase& testCase) {
    std::string line;
    for (size_t i = 0; i + 1 < testCase.arguments.size(); i += 2) {
        std::string option = testCase.arguments[i];
        if (option == "-w") option = "--imageWidth";
        if (option == "-c") option = "--complexity";
        line += " " + option + " " + shellQuoted(testCase.arguments[i + 1]);
    }
    return line;
}

std::vector<std::string> compatibleCases() {
    std::vector<std::string> folders;
    for (const std::string& folder : testCaseFolders())
        if (loadTestCase(folder).usdrecordCompatible()) folders.push_back(folder);
    return folders;
}

class CasesThroughUsdrecord : public ::testing::TestWithParam<std::string> {};

TEST_P(CasesThroughUsdrecord, MatchTheBaselineThroughTheSameDisplayTransform) {
    const TestCase testCase = loadTestCase(GetParam());
    const fs::path output = fs::path(HDHAIR_BINARY_DIR) / "testenv-cases-usdrecord" / testCase.name;
    fs::remove_all(output);
    fs::create_directories(output);
    std::string command = "HOME=" + shellQuoted(output.string()) + " " +
                          usdrecordWithHdHair(HDHAIR_PXR_BIN, HDHAIR_PXR_PYTHONPATH, HDHAIR_PLUGIN_RESOURCES) +
                          usdrecordArguments(testCase);
    if (!testCase.frames.empty()) command += " --frames " + shellQuoted(testCase.frames);
    command += " " + shellQuoted(testCase.stage) + " " + shellQuoted(framePattern(testCase, output.string(), "usdrecord"));
    std::string log;
    ASSERT_EQ(runCommand(command, &log), 0) << command << "\n" << log;
    const std::vector<std::string> actual = frameFiles(testCase, output.string(), "usdrecord");
    const std::vector<std::string> baselines = frameFiles(testCase, testCase.folder, "baseline");
    ASSERT_EQ(actual.size(), baselines.size());
    for (size_t frame = 0; frame < actual.size(); ++frame) {
        ASSERT_TRUE(fs::exists(actual[frame])) << actual[frame] << " was not written:\n" << log;
        writeImage(readImage(actual[frame]), actual[frame], {RenderingSpace::LinearRec709, nullptr, nullptr});
        const CaseVerdict verdict = compareWithBaseline(testCase, actual[frame], baselines[frame], output.string());
        std::cout << verdict.report << "\n";
        EXPECT_TRUE(verdict.passed) << testCase.description << "\n" << verdict.report;
    }
}

std::string caseName(const ::testing::TestParamInfo<std::string>& info) { return caseTestName(info.param); }

INSTANTIATE_TEST_SUITE_P(Testenv, CasesThroughUsdrecord, ::testing::ValuesIn(compatibleCases()), caseName);

// The split is real: most cases go through usdrecord, and those with
// hdHair-only settings do not.
TEST(CasesThroughUsdrecordSelection, TakesTheCasesWithoutHdHairOnlySettings) {
    size_t compatible = compatibleCases().size(), all = testCaseFolders().size();
    EXPECT_GE(compatible, 10u);
    EXPECT_LT(compatible, all);
    EXPECT_FALSE(loadTestCase(sourcePath("testenv/cases/sorting_exact")).usdrecordCompatible());
}

}  // namespace
