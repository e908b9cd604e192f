// hdhair-record as a user meets it: exit codes, one-line reasons, outputs,
// frames and --stats. Each test runs the real binary.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "Commands.h"

#include "hdHair/image/ImageComparison.h"
#include "hdHair/image/ImageWriter.h"

#include <OpenImageIO/imagebuf.h>

using namespace hdhair;
namespace fs = std::filesystem;

namespace {

struct RecordRun {
    int exitCode = -1;
    std::string output;  // stdout and stderr together
};

// These tests exercise the embedded reader's messages and stats, so they ask
// for it (builds with OpenUSD default to --reader usd), unless a test picks one.
RecordRun record(const std::string& arguments, const std::string& environment = "") {
    std::string reader = arguments.find("--reader") == std::string::npos ? "--reader embedded " : "";
    RecordRun run;
    run.exitCode = hdhair::testenv::runCommand(environment + " " HDHAIR_RECORD " " + reader + arguments, &run.output);
    return run;
}

std::string example(const std::string& name) { return std::string(HDHAIR_SOURCE_DIR) + "/examples/" + name; }

class HdhairRecord : public ::testing::Test {
protected:
    void SetUp() override {
        directory = fs::temp_directory_path() /
                    ("hdhair-record-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        fs::remove_all(directory);
        fs::create_directories(directory);
    }
    void TearDown() override { fs::remove_all(directory); }
    std::string file(const std::string& name) const { return (directory / name).string(); }
    std::string write(const std::string& name, const std::string& text) const {
        std::ofstream(directory / name) << text;
        return file(name);
    }
    fs::path directory;
};

}  // namespace

TEST_F(HdhairRecord, RendersAnExampleWithItsCameraAndReportsStats) {
    RecordRun run = record("--camera /World/main_cam --imageWidth 200 --stats " + file("stats.json") + " " +
                     example("straight_strands.usda") + " " + file("out.png"));
    ASSERT_EQ(run.exitCode, 0) << run.output;
    Image image = readImage(file("out.png"));
    EXPECT_EQ(image.width, 200);
    EXPECT_EQ(image.height, 145);  // usdrecord's rule: floor(200 / (20.955 / 15.2908)) = floor(145.9)

    nlohmann::json stats = nlohmann::json::parse(std::ifstream(file("stats.json")));
    const nlohmann::json& frame = stats["frames"][0];
    EXPECT_EQ(frame["prims"]["basisCurves"], 1);
    EXPECT_EQ(frame["curves"], 40);
    EXPECT_EQ(frame["segments"], 40 * 4);  // 7 catmullRom points: 4 spans each
    EXPECT_EQ(frame["camera"], "/World/main_cam");
    EXPECT_EQ(frame["settings"]["complexity"], "low");
    // The strands' tips are thinner than a pixel: blended coverage. Their
    // long straight spans cover about 26 pixels each, over
    // strandRasterMaxFragmentsPerSpan, so the default (strandRaster=auto)
    // keeps the hardware rasteriser, drawing in the bin sort's order.
    EXPECT_EQ(frame["transparency"], "binSorted");
    EXPECT_EQ(frame["strandRaster"], "hardware");
    // --stats turns pass timing on: every pass that ran has its time, in the
    // list and on the plan's graph.
    bool strandsTimed = false, shadowsTimed = false, sorted = false;
    for (const auto& pass : frame["passes"]) {
        strandsTimed = strandsTimed || (pass["name"] == "strands" && pass["milliseconds"] > 0.0);
        shadowsTimed = shadowsTimed || (pass["name"] == "shadowDepth /World/key_light" && pass["milliseconds"] > 0.0);
        sorted = sorted || pass["name"] == "sort";
    }
    EXPECT_TRUE(strandsTimed && shadowsTimed && sorted) << frame.dump(2);
    EXPECT_NE(frame["passTiming"], "off");
    bool graphStrands = false;
    for (const auto& pass : frame["plan"]) {
        if (pass["pass"] != "strands") continue;
        graphStrands = pass["enabled"] == true && pass["milliseconds"] > 0.0 &&
                       pass["reads"] == nlohmann::json({"strands", "drawOrder", "color", "depth",
                                                        "deepOpacity /World/fill_light",
                                                        "deepOpacity /World/key_light"}) &&
                       pass["writes"] == nlohmann::json({"color", "depth"});
    }
    EXPECT_TRUE(graphStrands) << frame["plan"].dump(2);
    // Both lights cast: their maps were built in this first frame.
    EXPECT_EQ(frame["shadowMapsRebuilt"], 2);
    EXPECT_EQ(frame["shadowMapsKept"], 0);
}

// The plan in --stats: a stage without meshes builds neither mesh pass; the
// meshes stage builds both, and reports its triangles and refine level.
TEST_F(HdhairRecord, StatsShowTheMeshPassesOnlyForStagesWithMeshes) {
    auto framesOf = [&](const std::string& stage) {
        RecordRun run = record("--camera /World/main_cam --imageWidth 96 --complexity medium --stats " +
                               file("s.json") + " " + stage + " " + file("out.png"));
        EXPECT_EQ(run.exitCode, 0) << run.output;
        return nlohmann::json::parse(std::ifstream(file("s.json")))["frames"][0];
    };
    auto passNamed = [](const nlohmann::json& frame, const std::string& name) {
        for (const auto& pass : frame["plan"])
            if (pass["pass"] == name) return pass;
        return nlohmann::json();
    };
    const nlohmann::json hair = framesOf(example("straight_strands.usda"));
    for (const char* name : {"meshUpload", "meshes"}) {
        EXPECT_EQ(passNamed(hair, name)["enabled"], false) << name;
        EXPECT_EQ(passNamed(hair, name)["reason"], "no meshes") << name;
    }
    EXPECT_EQ(hair["meshTriangles"], 0);
    const nlohmann::json meshes =
        framesOf(std::string(HDHAIR_SOURCE_DIR) + "/testenv/stages/meshes.usda");
    EXPECT_EQ(passNamed(meshes, "meshUpload")["enabled"], true);
    EXPECT_EQ(passNamed(meshes, "meshes")["enabled"], true);
    // 96 triangles and quads: 12 + 12 triangles (3 quads each at level 1),
    // 72 quads (4 each): 360 quads, 720 triangles.
    EXPECT_EQ(meshes["meshTriangles"], 720);
    EXPECT_EQ(meshes["preparedMeshes"], 1);
    EXPECT_NE(passNamed(meshes, "meshes")["reason"].get<std::string>().find("720 triangles (refine level 1)"),
              std::string::npos)
        << passNamed(meshes, "meshes").dump();
}

// --frames reads the stage at every frame, but a prim that does not change
// keeps what was prepared and uploaded for it: a static stage sends nothing
// after its first frame, an animated one only its moving prims.
TEST_F(HdhairRecord, FramesPrepareAndUploadOnlyWhatChanges) {
    auto framesOf = [&](const std::string& stage) {
        RecordRun run = record("--camera /World/main_cam --imageWidth 96 --frames 1:3 --stats " + file("s.json") + " " +
                               stage + " " + file("f.###.png"));
        EXPECT_EQ(run.exitCode, 0) << run.output;
        return nlohmann::json::parse(std::ifstream(file("s.json")))["frames"];
    };
    nlohmann::json still = framesOf(example("wavy_strands.usda"));
    ASSERT_EQ(still.size(), 3u);
    EXPECT_EQ(still[0]["uploadedSegments"], still[0]["segments"]);
    for (size_t frame = 1; frame < 3; ++frame) {
        EXPECT_EQ(still[frame]["preparedPrims"], 0) << frame;
        EXPECT_EQ(still[frame]["uploadedSegments"], 0) << frame;
    }
    // testenv/stages/xforms.usda: one of its prims has an animated transform.
    nlohmann::json animated = framesOf(std::string(HDHAIR_SOURCE_DIR) + "/testenv/stages/xforms.usda");
    for (size_t frame = 1; frame < 3; ++frame) {
        EXPECT_EQ(animated[frame]["preparedPrims"], 1) << frame;
        EXPECT_GT(animated[frame]["uploadedSegments"], 0) << frame;
        EXPECT_LT(animated[frame]["uploadedSegments"], animated[frame]["segments"]) << frame;
    }
}

TEST_F(HdhairRecord, ExrOutputIsLinearHalfFloatWithAlpha) {
    // The same frame as EXR and as PNG: the PNG's straight sRGB colour must be
    // the EXR's pre-multiplied linear colour, un-premultiplied and encoded.
    RecordRun run = record("--imageWidth 64 " + example("wavy_strands.usda") + " " + file("out.exr"));
    ASSERT_EQ(run.exitCode, 0) << run.output;
    RecordRun png = record("--imageWidth 64 " + example("wavy_strands.usda") + " " + file("out.png"));
    ASSERT_EQ(png.exitCode, 0) << png.output;
    Image linear = readImage(file("out.exr")), display = readImage(file("out.png"));
    ASSERT_EQ(linear.channels, 4);
    EXPECT_EQ(linear.width, 64);
    ASSERT_EQ(display.pixels.size(), linear.pixels.size());
    auto srgbEncoded = [](double c) { return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055; };
    int compared = 0;
    for (size_t p = 0; p < linear.pixels.size(); p += 4) {
        for (size_t c = 0; c < 4; ++c) {
            float value = linear.pixels[p + c];
            ASSERT_EQ(glm::unpackHalf1x16(glm::packHalf1x16(value)), value) << "not a half float";
        }
        double alpha = linear.pixels[p + 3];
        if (alpha < 0.25) continue;  // little coverage: 8-bit straight colour is coarse there
        ++compared;
        EXPECT_NEAR(display.pixels[p + 3], alpha, 0.6 / 255.0);
        for (size_t c = 0; c < 3; ++c)
            EXPECT_NEAR(display.pixels[p + c], srgbEncoded(std::min(linear.pixels[p + c] / alpha, 1.0)), 1.5 / 255.0)
                << "pixel " << p / 4 << " channel " << c;
    }
    EXPECT_GT(compared, 600) << "the strands cover about 860 such pixels at 64 px";
}

// EXR stays scene-linear, named and with its primaries in the metadata;
// display formats go through the chosen transform, recorded in --stats.
TEST_F(HdhairRecord, ColourManagementFollowsUsdrecordsModesAndOcio) {
    const std::string stage = example("wavy_strands.usda");
    RecordRun exr = record("--imageWidth 48 --colorCorrectionMode openColorIO " + stage + " " + file("l.exr"));
    ASSERT_EQ(exr.exitCode, 0) << exr.output;
    OIIO::ImageBuf exrFile(file("l.exr"));
    ASSERT_TRUE(exrFile.init_spec(file("l.exr"), 0, 0));
    EXPECT_EQ(exrFile.spec().get_string_attribute("colorSpace"), "lin_rec709");
    float chromaticities[8] = {};
    ASSERT_TRUE(exrFile.spec().getattribute("chromaticities", OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8), chromaticities));
    EXPECT_NEAR(chromaticities[0], 0.64f, 1e-6f);   // Rec.709 red x
    EXPECT_NEAR(chromaticities[7], 0.329f, 1e-6f);  // D65 white y
    const Image linear = readImage(file("l.exr"));

    // The Raw view shows un-premultiplied linear values as they are.
    RecordRun raw = record("--imageWidth 48 --colorCorrectionMode openColorIO --ocioView Raw --stats " +
                           file("s.json") + " " + stage + " " + file("raw.png"));
    ASSERT_EQ(raw.exitCode, 0) << raw.output;
    const Image rawImage = readImage(file("raw.png"));
    int compared = 0;
    for (size_t p = 0; p < linear.pixels.size(); p += 4) {
        const float alpha = linear.pixels[p + 3];
        if (alpha < 0.5f) continue;
        ++compared;
        for (size_t c = 0; c < 3; ++c)
            EXPECT_NEAR(rawImage.pixels[p + c], std::min(linear.pixels[p + c] / alpha, 1.0f), 1.0 / 255.0) << p / 4;
    }
    EXPECT_GT(compared, 50);
    nlohmann::json color = nlohmann::json::parse(std::ifstream(file("s.json")))["frames"][0]["color"];
    EXPECT_EQ(color["mode"], "openColorIO");
    EXPECT_EQ(color["display"], "sRGB");
    EXPECT_EQ(color["view"], "Raw");
    EXPECT_EQ(color["look"], "");
    EXPECT_EQ(color["on"], "cpu");
    EXPECT_NE(color["config"].get<std::string>().find("share/hdhair/ocio/config.ocio"), std::string::npos);

    // disabled: linear values straight into 8 bits, the same as the Raw view.
    RecordRun disabled = record("--imageWidth 48 --colorCorrectionMode disabled " + stage + " " + file("off.png"));
    ASSERT_EQ(disabled.exitCode, 0) << disabled.output;
    EXPECT_EQ(readImage(file("off.png")).pixels, rawImage.pixels);

    // The GPU path: the same picture within an 8-bit step, its pass timed.
    RecordRun gpu = record("--imageWidth 48 --colorCorrectionMode openColorIO --ocioView 'ACES 1.0 SDR-video' "
                           "--displayTransformOn gpu --stats " + file("g.json") + " " + stage + " " + file("gpu.png"));
    RecordRun cpu = record("--imageWidth 48 --colorCorrectionMode openColorIO --ocioView 'ACES 1.0 SDR-video' " +
                           stage + " " + file("cpu.png"));
    ASSERT_EQ(gpu.exitCode, 0) << gpu.output;
    ASSERT_EQ(cpu.exitCode, 0) << cpu.output;
    const Image gpuImage = readImage(file("gpu.png")), cpuImage = readImage(file("cpu.png"));
    ASSERT_EQ(gpuImage.pixels.size(), cpuImage.pixels.size());
    for (size_t i = 0; i < gpuImage.pixels.size(); ++i) ASSERT_NEAR(gpuImage.pixels[i], cpuImage.pixels[i], 1.0 / 255.0);
    nlohmann::json gpuFrame = nlohmann::json::parse(std::ifstream(file("g.json")))["frames"][0];
    EXPECT_EQ(gpuFrame["color"]["on"], "gpu");
    bool timed = false;
    for (const auto& pass : gpuFrame["passes"]) timed = timed || (pass["name"] == "displayTransform" && pass["milliseconds"] > 0.0);
    EXPECT_TRUE(timed) << gpuFrame["passes"].dump();

    // Names the config lacks are one-line errors listing the valid ones.
    RecordRun badView = record("--colorCorrectionMode openColorIO --ocioView Filmic " + stage + " " + file("b.png"));
    EXPECT_EQ(badView.exitCode, 1);
    EXPECT_EQ(badView.output.find("hdhair-record: error: display 'sRGB' of the OCIO config"), 0u) << badView.output;
    EXPECT_NE(badView.output.find("(views: sRGB, ACES 1.0 SDR-video, Raw)\n"), std::string::npos) << badView.output;
    RecordRun badMode = record("--colorCorrectionMode film " + stage + " " + file("b.png"));
    EXPECT_EQ(badMode.output,
              "hdhair-record: error: --colorCorrectionMode must be disabled, sRGB or openColorIO, not 'film'\n");
    RecordRun lookWithoutOcio = record("--ocioLook Brighter " + stage + " " + file("b.png"));
    EXPECT_EQ(lookWithoutOcio.exitCode, 1);
    EXPECT_NE(lookWithoutOcio.output.find("need --colorCorrectionMode openColorIO"), std::string::npos);
}

// renderingSpace=ACEScg: the EXR holds ACEScg, named and with AP1 primaries
// and the ACES white; the display image starts from ACEScg, so it shows what
// the lin_rec709 render shows (the groom's shading is linear in its colours
// under the white camera light).
TEST_F(HdhairRecord, AnAcesCgRenderIsWrittenAndShownAsAcesCg) {
    const std::string stage = example("wavy_strands.usda");
    RecordRun exr = record("--imageWidth 48 -s renderingSpace=ACEScg --stats " + file("s.json") + " " + stage + " " +
                           file("ap1.exr"));
    ASSERT_EQ(exr.exitCode, 0) << exr.output;
    OIIO::ImageBuf exrFile(file("ap1.exr"));
    ASSERT_TRUE(exrFile.init_spec(file("ap1.exr"), 0, 0));
    EXPECT_EQ(exrFile.spec().get_string_attribute("colorSpace"), "ACEScg");
    float chromaticities[8] = {};
    ASSERT_TRUE(exrFile.spec().getattribute("chromaticities", OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8), chromaticities));
    EXPECT_NEAR(chromaticities[0], 0.713f, 1e-6f);    // AP1 red x
    EXPECT_NEAR(chromaticities[6], 0.32168f, 1e-6f);  // ACES white x
    EXPECT_EQ(nlohmann::json::parse(std::ifstream(file("s.json")))["frames"][0]["color"]["renderingSpace"], "ACEScg");

    for (const char* view : {"sRGB", "'ACES 1.0 SDR-video'"}) {
        const std::string options = std::string("--imageWidth 48 --colorCorrectionMode openColorIO --ocioView ") + view;
        ASSERT_EQ(record(options + " -s renderingSpace=ACEScg " + stage + " " + file("ap1.png")).exitCode, 0);
        ASSERT_EQ(record(options + " " + stage + " " + file("rec709.png")).exitCode, 0);
        const ImageComparison comparison =
            compareImages(readImage(file("ap1.png")), readImage(file("rec709.png")), exactWithin(1.5 / 255.0));
        EXPECT_TRUE(comparison.passed) << view << ": " << comparison.description;
    }
}

TEST_F(HdhairRecord, FramesFillTheOutputPlaceholder) {
    std::string stage = std::string(HDHAIR_SOURCE_DIR) + "/testenv/stages/xforms.usda";
    RecordRun run = record("--frames 1:10x9 --imageWidth 48 " + stage + " " + file("frame.####.png"));
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_TRUE(fs::exists(file("frame.0001.png")));
    EXPECT_TRUE(fs::exists(file("frame.0010.png")));
    // The stage's translate is animated: each frame shows its own time.
    EXPECT_NE(readImage(file("frame.0001.png")).pixels, readImage(file("frame.0010.png")).pixels);
    RecordRun noPlaceholder = record("--frames 1:2 " + stage + " " + file("frame.png"));
    EXPECT_NE(noPlaceholder.exitCode, 0);
    EXPECT_NE(noPlaceholder.output.find("needs a '#' placeholder"), std::string::npos) << noPlaceholder.output;
}

// interactiveBudgetMs sets the previews interactive Hydra hosts show; a
// recorder writes full frames only, so asking for previews is a warning and
// the frames are rendered without any (through OpenUSD too).
TEST_F(HdhairRecord, AskingForPreviewsWarnsThatARecorderWritesFullFramesOnly) {
    for (const char* reader : {"embedded", "usd"}) {
#if !HDHAIR_WITH_USD
        if (std::string(reader) == "usd") continue;
#endif
        RecordRun run = record(std::string("--reader ") + reader + " -s interactiveBudgetMs=50 --imageWidth 48 --stats " +
                               file("stats.json") + " " + example("straight_strands.usda") + " " + file("o.png"));
        ASSERT_EQ(run.exitCode, 0) << run.output;
        EXPECT_NE(run.output.find("hdhair-record: warning: interactiveBudgetMs=50 has no effect here: it sets the "
                                  "previews interactive Hydra hosts (usdview) show, and hdhair-record writes full "
                                  "frames only\n"),
                  std::string::npos)
            << run.output;
        nlohmann::json stats = nlohmann::json::parse(std::ifstream(file("stats.json")));
        EXPECT_EQ(stats["frames"][0]["settings"]["interactiveBudgetMs"], 0) << reader;
    }
    RecordRun quiet = record("--imageWidth 48 " + example("straight_strands.usda") + " " + file("o.png"));
    ASSERT_EQ(quiet.exitCode, 0) << quiet.output;
    EXPECT_EQ(quiet.output.find("interactiveBudgetMs"), std::string::npos) << quiet.output;
}

TEST_F(HdhairRecord, ExplainPrintsThePlanAndVerbosePrintsPassTimes) {
    RecordRun run = record("--explain --verbose --imageWidth 64 " + example("straight_strands.usda") + " " + file("o.png"));
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_NE(run.output.find("plan (earliest time)"), std::string::npos) << run.output;
    // Pass names make a column as wide as the longest ("shadowDepth /World/fill_light").
    EXPECT_NE(run.output.find("  strands                       on   160 segments, binSorted"), std::string::npos)
        << run.output;
    EXPECT_NE(run.output.find("  deepOpacity /World/key_light  on   rebuilt: a new shadow-casting light"),
              std::string::npos)
        << run.output;
    EXPECT_NE(run.output.find("readback"), std::string::npos) << run.output;
}

// --quality picks a preset, --setting wins over it, --explain says which
// chose each setting and --stats keeps it; a preset with supersampling still
// writes an image of the asked width.
TEST_F(HdhairRecord, QualityPresetIsExplainedAndExplicitSettingsWin) {
    RecordRun run = record("--quality high --setting shadowLayers=3 --explain --imageWidth 64 --stats " +
                           file("stats.json") + " " + example("straight_strands.usda") + " " + file("o.png"));
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_NE(run.output.find("  quality=high, complexity low\n"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("  shadowLayers           3            explicit (wins over quality=high's 15)\n"),
              std::string::npos)
        << run.output;
    EXPECT_NE(run.output.find("  supersampling          2            quality=high\n"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("supersampleResolve"), std::string::npos) << run.output;
    const nlohmann::json frame = nlohmann::json::parse(std::ifstream(file("stats.json")))["frames"][0];
    EXPECT_EQ(frame["settings"]["quality"], "high");
    EXPECT_EQ(frame["settings"]["shadowLayers"], 3);
    EXPECT_EQ(frame["settings"]["sortBins"], 256);  // high leaves the bins at the default
    EXPECT_EQ(frame["supersampling"], 2);
    EXPECT_EQ(frame["image"]["width"], 64);
    EXPECT_EQ(frame["settingOrigins"]["supersampling"]["source"], "quality=high");
    EXPECT_EQ(frame["settingOrigins"]["shadowLayers"]["overriddenPreset"], "15");
    const Image written = readImage(file("o.png"));
    EXPECT_EQ(written.width, 64);

    RecordRun bad = record("--quality ultra " + example("straight_strands.usda") + " " + file("o.png"));
    EXPECT_EQ(bad.exitCode, 1);
    EXPECT_EQ(bad.output, "hdhair-record: error: --quality must be preview, default, high or reference, not 'ultra'\n");
    RecordRun gpu = record("--quality high --displayTransformOn gpu " + example("straight_strands.usda") + " " +
                           file("o.png"));
    EXPECT_EQ(gpu.exitCode, 1);
    EXPECT_EQ(gpu.output, "hdhair-record: error: supersampling=2 needs the display transform on the CPU "
                          "(--displayTransformOn cpu): it must follow the box filter\n");
}

TEST_F(HdhairRecord, MissingStageIsAOneLineError) {
    RecordRun run = record(file("missing.usda") + " " + file("out.png"));
    EXPECT_EQ(run.exitCode, 1);
    EXPECT_EQ(run.output, "hdhair-record: error: cannot open '" + file("missing.usda") +
                              "': No such file or directory\n");
    EXPECT_FALSE(fs::exists(file("out.png")));
}

TEST_F(HdhairRecord, MalformedStageNamesFileLineAndColumn) {
    std::string stage = write("bad.usda", "#usda 1.0\ndef BasisCurves \"hair\" {\n    int[] curveVertexCounts = [4,\n}\n");
    RecordRun run = record(stage + " " + file("out.png"));
    EXPECT_EQ(run.exitCode, 1);
    EXPECT_EQ(run.output.rfind("hdhair-record: error: " + stage + ":4:", 0), 0u) << run.output;
    EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << run.output;
}

TEST_F(HdhairRecord, BadArgumentsAreOneLineErrors) {
    std::string stage = example("straight_strands.usda");
    RecordRun badSetting = record("--setting bogus=1 " + stage + " " + file("o.png"));
    EXPECT_EQ(badSetting.exitCode, 1);
    EXPECT_EQ(badSetting.output.rfind("hdhair-record: error: unknown setting 'bogus'", 0), 0u) << badSetting.output;
    RecordRun badCamera = record("--camera /World/nope " + stage + " " + file("o.png"));
    EXPECT_EQ(badCamera.exitCode, 1);
    EXPECT_NE(badCamera.output.find("no camera at '/World/nope' (cameras: /World/main_cam)"), std::string::npos)
        << badCamera.output;
    RecordRun badExtension = record(stage + " " + file("o.bmpx"));
    EXPECT_EQ(badExtension.exitCode, 1);
    EXPECT_NE(badExtension.output.find("unsupported image extension"), std::string::npos);
    RecordRun badGl = record("--gl vulkan " + stage + " " + file("o.png"));
    EXPECT_EQ(badGl.output, "hdhair-record: error: --gl must be egl or osmesa\n");
    RecordRun noArguments = record("");
    EXPECT_NE(noArguments.exitCode, 0);
}

// A farm job fails before rendering when its outputs cannot be written, and
// a failed write leaves neither a partial image nor a temporary file.
TEST_F(HdhairRecord, OutputTargetsAreCheckedBeforeRenderingAndFailuresLeaveNothing) {
    const std::string stage = example("straight_strands.usda");
    RecordRun stats = record("--imageWidth 32 --stats /nonexistent/s.json " + stage + " " + file("o.png"));
    EXPECT_EQ(stats.exitCode, 1);
    EXPECT_EQ(stats.output, "hdhair-record: error: cannot write --stats file '/nonexistent/s.json': folder "
                            "'/nonexistent' does not exist\n");
    EXPECT_FALSE(fs::exists(file("o.png"))) << "rendered before the --stats target was checked";
    RecordRun frames = record("--imageWidth 32 --frames 1:2 " + stage + " /nonexistent/f.#.png");
    EXPECT_EQ(frames.output, "hdhair-record: error: cannot write '/nonexistent/f.#.png': folder '/nonexistent' does "
                             "not exist\n");
    // The target is a folder: rendering happens, the rename fails, nothing is left behind.
    fs::create_directories(file("taken.png"));
    RecordRun taken = record("--imageWidth 32 " + stage + " " + file("taken.png"));
    EXPECT_EQ(taken.exitCode, 1);
    EXPECT_EQ(taken.output.rfind("hdhair-record: error: cannot write '" + file("taken.png") + "': ", 0), 0u)
        << taken.output;
    for (const auto& entry : fs::directory_iterator(directory))
        EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
}

TEST_F(HdhairRecord, NoGlContextIsAClearErrorNotACrash) {
    RecordRun run = record("--gl egl " + example("straight_strands.usda") + " " + file("o.png"),
                     "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json");
    // 75 (EX_TEMPFAIL): the machine failed the frame, not its input, so a
    // farm may try it again; an input error stays 1.
    EXPECT_EQ(run.exitCode, 75);
    EXPECT_EQ(run.output.rfind("hdhair-record: error: no usable OpenGL 4.5 context through EGL (tried: ", 0), 0u)
        << run.output;
    EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << run.output;
}

TEST_F(HdhairRecord, OsMesaFallbackRenders) {
    RecordRun run = record("--gl osmesa --imageWidth 64 " + example("straight_strands.usda") + " " + file("o.exr"));
    ASSERT_EQ(run.exitCode, 0) << run.output;
    RecordRun fromEnvironment =
        record("--imageWidth 64 " + example("straight_strands.usda") + " " + file("e.exr"), "HDHAIR_GL=osmesa");
    ASSERT_EQ(fromEnvironment.exitCode, 0) << fromEnvironment.output;
    RecordRun egl = record("--gl egl --imageWidth 64 " + example("straight_strands.usda") + " " + file("g.exr"));
    ASSERT_EQ(egl.exitCode, 0) << egl.output;
    // The same picture through either context: llvmpipe draws both, so only
    // a strand edge may land elsewhere.
    Image osmesa = readImage(file("o.exr"));
    ImageComparison againstEgl = compareImages(osmesa, readImage(file("g.exr")), {1.0 / 255.0, 0.0025, 0.25, 4});
    EXPECT_TRUE(againstEgl.passed) << againstEgl.description;
    EXPECT_GT(againstEgl.coveredPixels, 300u) << "the strands were drawn";
    EXPECT_EQ(readImage(file("e.exr")).pixels, osmesa.pixels) << "HDHAIR_GL=osmesa is --gl osmesa";
}

TEST_F(HdhairRecord, HelpListsUsdrecordOptions) {
    RecordRun run = record("--help");
    EXPECT_EQ(run.exitCode, 0);
    for (const char* option : {"--camera", "--imageWidth", "--frames", "--defaultTime", "--complexity", "--setting",
                               "--gl", "--stats", "--colorCorrectionMode", "--ocioConfig", "--ocioDisplay",
                               "--ocioView", "--ocioColorSpace", "--ocioLook", "--displayTransformOn"})
        EXPECT_NE(run.output.find(option), std::string::npos) << option;
    RecordRun settings = record("--help-settings");
    EXPECT_EQ(settings.exitCode, 0);
    EXPECT_NE(settings.output.find("maxSegmentsPerSpan"), std::string::npos);
}

// docs/settings.md's table is what --help-settings --format markdown prints
// from the descriptors, so the reference cannot drift from the code.
TEST_F(HdhairRecord, TheSettingsReferenceIsWhatTheDescriptorsSay) {
    RecordRun markdown = record("--help-settings --format markdown");
    ASSERT_EQ(markdown.exitCode, 0) << markdown.output;
    EXPECT_EQ(markdown.output.rfind("| setting | values | default | meaning |\n", 0), 0u) << markdown.output;
    EXPECT_NE(markdown.output.find("| `maxSegmentsPerSpan` | integer 1 to 64 | `8` |"), std::string::npos)
        << markdown.output;
    std::ifstream file(std::string(HDHAIR_SOURCE_DIR) + "/docs/settings.md");
    const std::string document((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    const std::string begin = "<!-- generated: hdhair-record --help-settings --format markdown";
    const std::string end = "<!-- end of generated table -->";
    const size_t from = document.find('\n', document.find(begin));
    const size_t to = document.find(end);
    ASSERT_NE(document.find(begin), std::string::npos) << "docs/settings.md has no generated table";
    ASSERT_NE(to, std::string::npos);
    EXPECT_EQ(document.substr(from + 1, to - from - 1), markdown.output)
        << "docs/settings.md differs from the descriptors: write it again with "
           "hdhair-record --help-settings --format markdown";
    RecordRun unknown = record("--help-settings --format xml");
    EXPECT_EQ(unknown.exitCode, 2);
    EXPECT_EQ(unknown.output, "hdhair-record: error: --format must be text or markdown, not 'xml'\n");
}

#if HDHAIR_WITH_USD
TEST_F(HdhairRecord, UsdReaderReportsThePluginsPassesAndPlan) {
    RecordRun run = record("--reader usd --verbose --explain --camera /World/main_cam --imageWidth 120 --stats " +
                           file("stats.json") + " " + example("straight_strands.usda") + " " + file("out.png"));
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_NE(run.output.find("through OpenUSD and the HdHair plugin"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("plugin passes: "), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("hdhair-record: plan ("), std::string::npos) << run.output;
    nlohmann::json stats = nlohmann::json::parse(std::ifstream(file("stats.json")));
    const nlohmann::json& frame = stats["frames"][0];
    EXPECT_EQ(frame["reader"], "usd");
    EXPECT_EQ(frame["curves"], 40);
    EXPECT_EQ(frame["transparency"], "binSorted");
    bool strandsTimed = false;
    // The plugin timed its passes: --stats reached it as passTimings=true.
    for (const auto& pass : frame["passes"])
        strandsTimed = strandsTimed || (pass["name"] == "strands" && pass["milliseconds"] > 0.0);
    EXPECT_TRUE(strandsTimed) << frame.dump(2);
}

// The preset reaches the Hydra plugin as a render setting: its frame has the
// preset's settings, names the preset as their origin, and is supersampled.
TEST_F(HdhairRecord, UsdReaderRendersTheQualityPresetThroughThePlugin) {
    RecordRun run = record("--reader usd --quality high --explain --camera /World/main_cam --imageWidth 64 --stats " +
                           file("stats.json") + " " + example("straight_strands.usda") + " " + file("out.png"));
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_NE(run.output.find("  supersampling          2            quality=high\n"), std::string::npos) << run.output;
    const nlohmann::json frame = nlohmann::json::parse(std::ifstream(file("stats.json")))["frames"][0];
    EXPECT_EQ(frame["settings"]["quality"], "high");
    EXPECT_EQ(frame["settings"]["shadowLayers"], 15);
    EXPECT_EQ(frame["settingOrigins"]["shadowLayers"]["source"], "quality=high");
    EXPECT_EQ(frame["supersampling"], 2);
    EXPECT_EQ(frame["image"]["width"], 64);
}
#else
TEST_F(HdhairRecord, UsdReaderWithoutOpenUsdIsAOneLineError) {
    RecordRun run = record("--reader usd " + example("straight_strands.usda") + " " + file("o.png"));
    EXPECT_EQ(run.exitCode, 1);
    EXPECT_EQ(run.output, "hdhair-record: error: --reader usd needs hdHair built with OpenUSD (see README, 'Hydra "
                          "plugin'); this build has only --reader embedded\n");
}
#endif
