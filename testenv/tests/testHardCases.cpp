// Hard cases (docs/hard-cases.md) that no other test covers, table-driven: small
// stages written here, read by the embedded reader and rendered, each
// checked for finite values in every AOV (colour, depth, ids) and for the
// warning that names the prim and attribute; and hdhair-record's one-line
// errors for what cannot be repaired. docs/hard-cases.md lists every case
// with the test that checks it.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/image/ImageWriter.h"
#include "hdHair/render/FrameMemory.h"
#include "hdHair/plan/FramingBounds.h"
#include "hdHair/plan/RenderPlan.h"
#include "hdHair/render/Renderer.h"
#include "hdHair/scene/SceneValidation.h"
#include "testenv/tests/BadInputStages.h"
#include "testenv/tests/Commands.h"
#include "testenv/tests/DistantLight.h"
#include "testenv/tests/HorizontalStrands.h"
#include "testenv/tests/OrthographicView.h"
#include "testenv/tests/StageRendering.h"

namespace hdhair::testenv {
namespace {

namespace fs = std::filesystem;

std::string writeStage(const std::string& name, const std::string& text) {
    const fs::path folder = fs::temp_directory_path() / "hdhair-hard-cases";
    fs::create_directories(folder);
    const fs::path path = folder / (name + ".usda");
    std::ofstream(path) << text;
    return path.string();
}

bool allFinite(const Image& image) {
    for (float value : image.pixels)
        if (!std::isfinite(value)) return false;
    return true;
}

// Searches "where: message", so that either may name the prim.
bool anyWarningContains(const std::vector<Diagnostic>& warnings, const std::string& text) {
    for (const Diagnostic& warning : warnings)
        if ((warning.where + ": " + warning.message).find(text) != std::string::npos) return true;
    return false;
}

// `text` with its first `from` replaced by `to` (which must be there).
std::string replaced(std::string text, const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

std::string outputPath(const std::string& name) {
    return (fs::temp_directory_path() / "hdhair-hard-cases" / name).string();
}

std::string describe(const std::vector<Diagnostic>& warnings) {
    std::string text;
    for (const Diagnostic& warning : warnings) text += warning.where + ": " + warning.message + "\n";
    return text;
}

struct RenderedStage {
    RenderResult result;
    std::vector<Diagnostic> warnings;
};

// Renders `stagePath` through /cam, 64 pixels wide, with ids, as
// hdhair-record would (the camera checked first).
RenderedStage renderThroughCam(const std::string& stagePath, const std::vector<std::string>& settings = {}) {
    StageRenderRequest request;
    request.stagePath = stagePath;
    request.camera = "/cam";
    request.imageWidth = 64;
    request.settings = settings;
    Diagnostics diagnostics;
    Scene scene = readStage(request, diagnostics);
    const CameraView camera =
        cameraViewFromPrim(checkedCamera(*scene.findCamera("/cam"), stagePath, diagnostics), request.imageWidth);
    RenderOutputs outputs;
    outputs.ids = true;
    RenderedStage rendered;
    rendered.result = sharedRenderer().render(scene, camera, stageSettings(request), diagnostics, outputs);
    rendered.warnings = diagnostics.warnings();
    return rendered;
}

void expectFiniteAovs(const RenderResult& result) {
    EXPECT_TRUE(allFinite(result.color));
    EXPECT_TRUE(allFinite(result.depth));
    for (const std::vector<int32_t>* ids : {&result.primIds, &result.instanceIds, &result.elementIds}) {
        ASSERT_EQ(ids->size(), size_t(result.color.width) * size_t(result.color.height));
        for (int32_t id : *ids) EXPECT_GE(id, -1);
    }
    for (float depth : result.depth.pixels) {
        EXPECT_GE(depth, 0.0f);
        EXPECT_LE(depth, 1.0f);
    }
}

// Each bad input is repaired or skipped with a warning naming the prim and
// attribute, and the frame stays finite in every AOV. One test for the whole
// table: each case is a 64-pixel frame, far cheaper than a process of its own.
TEST(HardCases, BadInputsWarnNameThePrimAndAttributeAndLeaveEveryAovFinite) {
    for (const InputCase& input : kBadInputs) {
        SCOPED_TRACE(input.name);
        const RenderedStage rendered = renderThroughCam(writeStage(input.name, stageText(input.hair, input.extra)));
        expectFiniteAovs(rendered.result);
        EXPECT_TRUE(anyWarningContains(rendered.warnings, input.warning))
            << "expected a warning containing '" << input.warning << "', got:\n"
            << describe(rendered.warnings);
        EXPECT_EQ(coverage(rendered.result.color) > 0.0, input.drawn);
    }
}

// A sun of intensity 1e6 (and a large Ks) makes values a half float cannot
// hold: the half EXR clamps them to 65504 and counts them, a float32 EXR
// keeps them exactly; neither holds an Inf.
TEST(HardCases, BrightValuesAreClampedInHalfExrAndExactInFloat32) {
    const RenderedStage rendered =
        renderThroughCam(writeStage("brightSun", stageText("", kDistant + " float inputs:intensity = 1e6\n}")),
                         {"kajiyaKay:specular=100"});
    expectFiniteAovs(rendered.result);
    float brightest = 0.0f;
    for (float value : rendered.result.color.pixels) brightest = std::max(brightest, value);
    ASSERT_GT(brightest, kHalfMax);

    const std::string half = outputPath("bright-half.exr"), full = outputPath("bright-float.exr");
    const ImageWriteReport halfReport = writeImage(rendered.result.color, half);
    ImageColor float32;
    float32.exrFloat32 = true;
    const ImageWriteReport fullReport = writeImage(rendered.result.color, full, float32);
    EXPECT_GT(halfReport.pixelsClampedToHalf, 0u);
    EXPECT_EQ(fullReport.pixelsClampedToHalf, 0u);
    const Image halfImage = readImage(half), fullImage = readImage(full);
    EXPECT_TRUE(allFinite(halfImage));
    EXPECT_TRUE(allFinite(fullImage));
    float halfMax = 0.0f;
    for (float value : halfImage.pixels) halfMax = std::max(halfMax, value);
    EXPECT_EQ(halfMax, kHalfMax);
    EXPECT_EQ(fullImage.pixels, rendered.result.color.pixels);
}

// Whatever slips past the input checks (here a light whose radiance is
// finite but whose shading overflows float) is replaced with a warning, never
// written as NaN or Inf.
TEST(HardCases, ShadingThatOverflowsFloatIsReplacedWithAWarning) {
    const RenderedStage rendered = renderThroughCam(
        writeStage("overflowingSun", stageText("", kDistant + " float inputs:intensity = 3e38\n}")),
        {"kajiyaKay:specular=100"});
    expectFiniteAovs(rendered.result);
    EXPECT_TRUE(anyWarningContains(rendered.warnings, "were not finite")) << describe(rendered.warnings);
}

// 100,000 lights: the first kMaxLights shade, the rest are left out with one
// warning, and the casting lights beyond shadowMemoryMB's maps shade
// unshadowed with one warning, not one each.
TEST(HardCases, AbsurdLightCountsAreCapped) {
    Scene scene;
    scene.setCurves(horizontalStrands("/hair", 0, 0, 0.0f, {-2.0, 0.0, 2.0}, 0.5, glm::vec3(0.5f), 1.0f));
    for (int i = 0; i < 100000; ++i) {
        char path[32];
        std::snprintf(path, sizeof path, "/lights/l%06d", i);
        // Grazing and parallel to the strands too: every direction is fine.
        scene.setLight(distantLightFrom(glm::dvec3(std::cos(i * 0.01), std::sin(i * 0.01), 0.3), path, 1e-3f));
    }
    Diagnostics diagnostics;
    RenderSettings settings;
    settings.set("lightsPerPass", "16");
    // 1 MB a map: 16 maps for the 1024 casting lights, quickly built.
    settings.set("shadowMapResolution", "256");
    settings.set("shadowMemoryMB", "16");
    const RenderResult result = sharedRenderer().render(scene, orthographicView(12.0, 32), settings, diagnostics);
    EXPECT_TRUE(allFinite(result.color));
    EXPECT_EQ(result.plan.recipe().lighting.lights.lights.size(), kMaxLights);
    EXPECT_EQ(result.plan.recipe().lighting.overCap, 100000 - kMaxLights);
    EXPECT_TRUE(anyWarningContains(diagnostics.warnings(), "the stage has 100000 lights, more than the 1024"))
        << describe(diagnostics.warnings());
    EXPECT_TRUE(anyWarningContains(diagnostics.warnings(), "shade unshadowed")) << describe(diagnostics.warnings());
    EXPECT_LT(diagnostics.warningCount(), 5u) << describe(diagnostics.warnings());
}

TEST(HardCases, ShadowMapBudgetIsAPowerOfTwoWithinMemoryAndArrayLayers) {
    EXPECT_EQ(shadowMapBudget(1024, 3, 1024), 64u);    // 16 MB a map
    EXPECT_EQ(shadowMapBudget(4096, 3, 1024), 4u);     // 256 MB a map
    EXPECT_EQ(shadowMapBudget(16384, 32, 1024), 0u);   // one map alone is over budget
    EXPECT_EQ(shadowMapBudget(16, 32, 65536), 256u);   // 2048 layers / 8 targets
    EXPECT_EQ(shadowMapBudget(1024, 3, 1000), 32u);    // 62 maps fit: the power of two below
}

// One point at 1e15 among hair a few units wide (finite, and short of the
// 1e18 past which curve preparation drops a curve): the framing camera
// leaves it out with a warning naming the prim, and frames the hair.
TEST(HardCases, AnOutlierPointDoesNotSetTheFramingBounds) {
    CurvesPrim hair = horizontalStrands("/hair", 0, 0, 0.0f, {-2.0, 0.0, 2.0}, 0.5, glm::vec3(0.5f), 1.0f);
    CurvesPrim stray = horizontalStrands("/stray", 1, 0, 0.0f, {1.0}, 0.5, glm::vec3(0.5f), 1.0f);
    stray.points[1] = glm::vec3(1e15f, 1.0f, 0.0f);
    Scene scene;
    scene.setCurves(hair);
    scene.setCurves(stray);
    Diagnostics diagnostics;
    const SceneBounds bounds = sharedRenderer().prepare(scene, RenderSettings{}, diagnostics);
    EXPECT_LT(bounds.max.x, 100.0);
    EXPECT_GT(bounds.max.x, 4.9);
    EXPECT_LT(bounds.min.x, -4.9);
    EXPECT_TRUE(anyWarningContains(diagnostics.warnings(), "the framing camera leaves them out"))
        << describe(diagnostics.warnings());
    EXPECT_EQ(diagnostics.warnings().back().where, "/stray");

    // Without the outlier nothing is left out and nothing is said.
    Scene plain;
    plain.setCurves(hair);
    Diagnostics quiet;
    const SceneBounds plainBounds = sharedRenderer().prepare(plain, RenderSettings{}, quiet);
    EXPECT_EQ(quiet.warningCount(), 0u) << describe(quiet.warnings());
    EXPECT_NEAR(plainBounds.max.x, 5.25, 1e-4);  // the strand's end plus half its width
}

// A frame whose images need more memory than the process can take is
// refused before anything is allocated, with the sizes and the widest image
// that fits; one that fits goes ahead.
TEST(HardCases, AFrameBeyondTheMemoryAvailableIsRefusedBeforeAllocating) {
    const AvailableMemory oneGigabyte{uint64_t(1) << 30, "ulimit -v"};
    EXPECT_NO_THROW(checkFrameFitsMemory(1024, 1024, RenderSettings(), false, false, 0, oneGigabyte));
    try {
        checkFrameFitsMemory(16384, 16384, RenderSettings(), false, false, 0, oneGigabyte);
        FAIL() << "a 16384-pixel frame was let through with 1 GB";
    } catch (const std::runtime_error& error) {
        EXPECT_EQ(std::string(error.what()),
                  "a 16384x16384 frame needs about 19.0 GB for its images (76 bytes a pixel), more than the 1.0 GB "
                  "this process can take (ulimit -v); at this shape at most 3758 pixels wide fits: lower the image "
                  "width");
    }
    // A Hydra host's own buffers count too.
    EXPECT_THROW(checkFrameFitsMemory(3700, 3700, RenderSettings(), false, false, 36, oneGigabyte),
                 std::runtime_error);
    // Multisampling multiplies the GL targets.
    EXPECT_GT(frameImageBytes(100, 100, 8, false, false), 4 * frameImageBytes(100, 100, 0, false, false));
}

// Hydra hands the renderer its own matrices: a NaN there is refused with a
// clear message rather than rendered blank.
TEST(HardCases, ANonFiniteCameraViewIsRefused) {
    Scene scene;
    scene.setCurves(horizontalStrands("/hair", 0, 0, 0.0f, {0.0}, 0.5, glm::vec3(0.5f), 1.0f));
    CameraView camera = orthographicView(12.0, 16);
    camera.view[3][0] = std::nan("");
    Diagnostics diagnostics;
    try {
        sharedRenderer().render(scene, camera, RenderSettings(), diagnostics);
        FAIL() << "rendered through a NaN camera";
    } catch (const std::invalid_argument& error) {
        EXPECT_NE(std::string(error.what()).find("the camera's view or projection is not finite"), std::string::npos);
    }
}

struct RecordRun {
    int exitCode = -1;
    std::string output;
};

RecordRun record(const std::string& arguments) {
    RecordRun run;
    run.exitCode = runCommand(std::string(HDHAIR_RECORD) + " --reader embedded " + arguments, &run.output);
    return run;
}

int lineCount(const std::string& text) { return int(std::count(text.begin(), text.end(), '\n')); }

// A lens that cannot be repaired (a zero focal length, a NaN transform) is a
// one-line error in both readers: testReaderVerdicts.cpp's catalogue.

// A bad clipping range has an obvious repair: USD's fallback, with a warning.
TEST(HardCases, ABadClippingRangeTakesUsdsFallbackWithAWarning) {
    for (const char* range : {"(0, 100)", "(5, 1)", "(nan, 100)", "(-1, inf)"}) {
        const std::string stage =
            writeStage("badClipping", replaced(stageText("", ""), "float2 clippingRange = (0.1, 100)",
                                               std::string("float2 clippingRange = ") + range));
        const RenderedStage rendered = renderThroughCam(stage);
        expectFiniteAovs(rendered.result);
        EXPECT_TRUE(anyWarningContains(rendered.warnings, "/cam.clippingRange:")) << range;
        EXPECT_TRUE(anyWarningContains(rendered.warnings, "using USD's fallback (1, 1000000)")) << range;
        EXPECT_GT(coverage(rendered.result.color), 0.0) << range;
    }
}

// An image taller than the GL driver's limits (a narrow aperture makes a
// 100-pixel-wide image 99,999 rows tall: float division, truncated as
// usdrecord does) is a one-line error before any allocation, not a crash or
// gigabytes of memory; the apertures' ratio is a warning before it.
TEST(HardCases, AnImageBeyondGlLimitsIsAOneLineError) {
    const std::string stage = writeStage(
        "tallImage", replaced(stageText("", ""), "float verticalAperture = 120", "float verticalAperture = 120000"));
    const RecordRun run = record("--camera /cam -w 100 '" + stage + "' '" + outputPath("tall.png") + "'");
    EXPECT_NE(run.exitCode, 0);
    // The error, after the warning that the apertures (1:1000) make so tall an image.
    EXPECT_EQ(lineCount(run.output), 2) << run.output;
    EXPECT_NE(run.output.find("hdhair-record: warning: " + stage + ": /cam.horizontalAperture, /cam.verticalAperture: "
                              "(120, 120000) make an image 0.001 times as wide as it is tall"),
              std::string::npos)
        << run.output;
    EXPECT_NE(run.output.find("hdhair-record: error: image size 100x99999 is outside what the GL driver supports"),
              std::string::npos)
        << run.output;
}

// The CLI's half EXR warns about clamped pixels and names the option that
// keeps them; --exrFloat32 keeps them without a word.
TEST(HardCases, HdhairRecordWarnsAboutHalfClampingAndExrFloat32KeepsValues) {
    const std::string stage = writeStage("brightSunCli", stageText("", kDistant + " float inputs:intensity = 1e6\n}"));
    const RecordRun half = record("--camera /cam -w 32 '" + stage + "' '" + outputPath("sun-half.exr") + "'");
    EXPECT_EQ(half.exitCode, 0) << half.output;
    EXPECT_NE(half.output.find("pixels exceed half float's largest value (65504) and were clamped to it; "
                               "--exrFloat32 writes them exactly"),
              std::string::npos)
        << half.output;
    const RecordRun full =
        record("--exrFloat32 --camera /cam -w 32 '" + stage + "' '" + outputPath("sun-float.exr") + "'");
    EXPECT_EQ(full.exitCode, 0) << full.output;
    EXPECT_EQ(full.output.find("clamped"), std::string::npos) << full.output;
    float brightest = 0.0f;
    for (float value : readImage(outputPath("sun-float.exr")).pixels) brightest = std::max(brightest, value);
    EXPECT_GT(brightest, kHalfMax);
}

// A frame that shows nothing because of bad input says so; an empty stage
// does not.
TEST(HardCases, AFrameThatDrawsNothingBecauseOfBadInputWarns) {
    // Every curve has a NaN point, so curve preparation drops them all.
    const std::string bad = writeStage(
        "nothingDrawable", replaced(stageText("", ""), "[(-5, -2, 0), (5, -2, 0), (-5, 0, 0), (5, 0, 0), (-5, 2, 0)",
                                    "[(nan, -2, 0), (5, -2, 0), (nan, 0, 0), (5, 0, 0), (nan, 2, 0)"));
    const RecordRun run = record("--camera /cam -w 32 '" + bad + "' '" + outputPath("nothing.png") + "'");
    EXPECT_EQ(run.exitCode, 0) << run.output;
    EXPECT_NE(run.output.find("nothing drawn: none of the stage's curves and mesh prims (1 and 0) has anything left"),
              std::string::npos)
        << run.output;

    const std::string offCamera =
        writeStage("offCamera", replaced(stageText("", ""), "double3 xformOp:translate = (0, 0, 10)",
                                         "double3 xformOp:translate = (0, 500, 10)"));
    const RecordRun away = record("--camera /cam -w 32 '" + offCamera + "' '" + outputPath("away.png") + "'");
    EXPECT_EQ(away.exitCode, 0) << away.output;
    EXPECT_NE(away.output.find("nothing drawn: the 3 segments and 0 triangles lie outside the camera's view"),
              std::string::npos)
        << away.output;

    const RecordRun empty =
        record("-w 32 '" + sourcePath("testenv/stages/empty.usda") + "' '" + outputPath("empty.png") + "'");
    EXPECT_EQ(empty.exitCode, 0) << empty.output;
    EXPECT_EQ(empty.output.find("nothing drawn"), std::string::npos) << empty.output;
}

}  // namespace
}  // namespace hdhair::testenv
