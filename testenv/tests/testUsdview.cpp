// Built and run only with OpenUSD: usdview, the host studios open first,
// starts with `--renderer HdHair` on a testenv stage under Xvfb, renders a
// frame through the plugin and quits. The exit code alone would pass with
// Storm, or with a plugin that failed to load and fell back, so the test
// reads the plugin's own frame line (TF_DEBUG=HDHAIR_FRAMES) and its numbers,
// and fails on any Python traceback or coding error usdview printed.

#include <unistd.h>

#include <filesystem>
#include <regex>
#include <string>

#include <gtest/gtest.h>

#include "Commands.h"

namespace fs = std::filesystem;
using hdhair::testenv::runCommand;

namespace {

struct UsdviewRun {
    int exitCode = -1;
    std::string output;  // stdout and stderr together
    std::smatch frame;  // the first frame line: width, height, curves, segments
    bool rendered = false;
};

UsdviewRun openInUsdview(const std::string& renderer, const std::string& stage) {
    // usdview keeps its window state under $HOME; a fresh home per test keeps
    // the user's and the other tests' state out of it.
    fs::path home = fs::temp_directory_path() / ("hdhair-usdview-" + renderer + "-" + std::to_string(::getpid()));
    fs::create_directories(home);
    UsdviewRun result;
    result.exitCode = runCommand("HOME=" + home.string() + " PYTHONPATH=" + HDHAIR_PXR_PYTHONPATH +
                                     " TF_DEBUG=HDHAIR_FRAMES PXR_PLUGINPATH_NAME=" + HDHAIR_PLUGIN_RESOURCES +
                                     " timeout 300 xvfb-run -a " + HDHAIR_PXR_BIN + "/usdview --renderer " + renderer +
                                     " --quitAfterStartup " + HDHAIR_SOURCE_DIR + "/" + stage,
                                 &result.output);
    fs::remove_all(home);
    static const std::regex frameLine(
        R"(hdHair: rendered a frame: (\d+)x(\d+), (\d+) curves, (\d+) segments)");
    result.rendered = std::regex_search(result.output, result.frame, frameLine);
    return result;
}

}  // namespace

TEST(Usdview, RendersTheStageThroughTheHdHairPluginAndQuits) {
    UsdviewRun usdview = openInUsdview("HdHair", "testenv/stages/instancing/root.usda");
    const std::string& output = usdview.output;
    EXPECT_EQ(usdview.exitCode, 0) << output;
    EXPECT_EQ(output.find("Traceback"), std::string::npos) << output;
    EXPECT_EQ(output.find("Coding Error"), std::string::npos) << output;
    EXPECT_EQ(output.find("Runtime Error"), std::string::npos) << output;
    ASSERT_TRUE(usdview.rendered) << "no frame line from the plugin:\n" << output;
    EXPECT_GT(std::stoi(usdview.frame[1]), 0);
    EXPECT_GT(std::stoi(usdview.frame[2]), 0);
    // The instancing stage: two prototypes' curves at every native instance
    // and PointInstancer index (testenv/stages/generate_stages.py).
    EXPECT_EQ(std::stoi(usdview.frame[3]), 24) << output;
    EXPECT_GT(std::stoi(usdview.frame[4]), 0) << output;
}

// The same check would pass vacuously if any usdview run printed a frame
// line: Storm, chosen instead, prints none.
TEST(Usdview, StormPrintsNoHdHairFrameLine) {
    UsdviewRun storm = openInUsdview("GL", "testenv/stages/instancing/root.usda");
    EXPECT_EQ(storm.exitCode, 0) << storm.output;
    EXPECT_FALSE(storm.rendered) << storm.output;
}
