// Image tests: every example and testenv stage renders through the engine and
// matches its checked-in baselines: the display image a user sees (8-bit
// sRGB PNG, straight alpha) and the linear image (half-float EXR,
// pre-multiplied), each compared by hdHair/image/ImageComparison.h over the
// pixels either image covers. Baselines are rendered at --complexity medium,
// so that a tessellation one level coarser is a defect they can show.
//
// Each case must also
// - match with its camera moved by 1/256 px, one step of llvmpipe's 8-bit
//   sub-pixel grid, so every strand vertex rounds the other way at once:
//   more than another CPU's float rounding moves, so the tolerance is loose
//   enough for edge jitter (EGL against OSMesa is checked below too);
// - fail for every defect that applies to its stage (BaselineDefects.h):
//   sorting off, Kd, Ks or shininess changed, one complexity level lower,
//   a light removed; so the tolerance is tight enough to catch a changed shade.
//
// To accept new pictures after an intended change:
//   HDHAIR_UPDATE_BASELINES=1 ctest -R Baseline     (fails, having rewritten them: review the PNGs in git)
// Failing renders are left in build/testenv-output/ for inspection.

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "BaselineDefects.h"
#include "StageRendering.h"
#include "TestStages.h"
#include "hdHair/image/ImageComparison.h"
#include "hdHair/image/ImageWriter.h"
#include "hdHair/plan/CameraView.h"
#include "hdHair/scene/Scene.h"
#include "hdHair/usda/SceneReader.h"
#include "testenv/tests/BaselineUpdates.h"

using namespace hdhair;
using namespace hdhair::testenv;
namespace fs = std::filesystem;

namespace {

struct BaselineTolerance {
    CoveredPixelTolerance display;  // the PNG: 8-bit sRGB values
    CoveredPixelTolerance linear;   // the EXR: linear pre-multiplied values
};

// Shades: a covered pixel may differ by 2/255 in the display image (8-bit
// rounding either side) and by 1/255 in linear values, and 0.25 % of covered
// pixels by more (up to 0.25). Measured: the sub-pixel shift moves at most
// 0.14 % that much (the framing camera, linear), the weakest defect 0.45 %
// (instancing, sorting off, linear; its strands share one colour), the next
// weakest 0.75 % (interpolations, one complexity level lower, linear).
// Edges: a strand edge landing one pixel over differs by up to 1 in a pixel.
// Each case allows the outliers (over 0.25) the sub-pixel shift makes in its
// images, measured, and half as many again (at least 3 more): a handful where
// strands are few and wide, more where many thin strands have many edges.
// The fewest outliers a defect makes where shades alone do not fail it: 28
// (hair parameters, one complexity level lower), 136 (composition, the same).
BaselineTolerance strandEdges(size_t outliers) {
    return {{2.0 / 255.0, 0.0025, 0.25, outliers}, {1.0 / 255.0, 0.0025, 0.25, outliers}};
}

// Strands self-shadowed by the camera light: the shadow follows each sample
// point along the strand, so the sub-pixel shift moves more shades a little.
// Measured: 0.30 % (wavy strands) and 0.37 % (framing camera) of covered
// pixels over 1/255 in linear values; allowed 0.55 %, half as much again,
// below the weakest defect's 0.75 %.
BaselineTolerance shadowedStrandEdges(size_t outliers) {
    BaselineTolerance tolerance = strandEdges(outliers);
    tolerance.linear.allowedShareOverThreshold = 0.0055;
    return tolerance;
}

// Per stage (all time codes of a stage share it), with the outliers the
// sub-pixel shift makes at the baseline width in brackets.
const std::map<std::string, BaselineTolerance>& baselineTolerances() {
    static const std::map<std::string, BaselineTolerance> tolerances = {
        {"straight_strands", strandEdges(81)},  // (54) 40 strands tapering to 0.02 cm
        {"wavy_strands", shadowedStrandEdges(90)},    // (60) 60 strands, sub-pixel at their tips
        {"framing_camera", shadowedStrandEdges(75)},  // (50) the wavy strands through the framing camera
        // 4,000 strands mostly under a pixel wide: the shift changes the
        // coverage of thousands of pixels a little rather than a few edges a
        // lot: 2.8 % of covered pixels move over 3/255 in the display image,
        // 3.5 % over 2/255 in linear values. The defects move 9.1 % (display)
        // and 11 % (linear) for one complexity level lower, 50 % or more for
        // the others.
        {"dense_clump", {{3.0 / 255.0, 0.05, 0.25, 33}, {2.0 / 255.0, 0.06, 0.25, 33}}},  // (22)
        {"bases", strandEdges(21)},            // (14)
        {"interpolations", strandEdges(8)},    // (5)
        {"hair_parameters", strandEdges(5)},   // (2)
        {"xforms", strandEdges(5)},            // (2)
        {"composition", strandEdges(23)},      // (15)
        {"materials", strandEdges(26)},        // (17)
        {"instancing", strandEdges(17)},       // (11)
        {"meshes", strandEdges(23)},           // (15) the head's silhouette and the hair over it
    };
    return tolerances;
}

struct BaselineCase {
    std::string name;   // names the baseline files
    std::string stage;  // names the tolerance
    StageRenderRequest request;
};

// One case per baseline time of every stage that has baselines
// (TestStages.h), and the framing camera (no --camera) on an example.
std::vector<BaselineCase> baselineCases() {
    std::vector<BaselineCase> cases;
    for (const TestStage& stage : testStages()) {
        for (double time : stage.baselineTimes) {
            std::string name = stage.name;
            if (stage.baselineTimes.size() > 1) name += "_time" + std::to_string(static_cast<int>(time));
            cases.push_back({name, stage.name, {stage.path, stage.camera, stage.baselineWidth, time, {},
                                                Complexity::Medium}});
        }
    }
    cases.push_back({"framing_camera", "framing_camera",
                     {"examples/wavy_strands.usda", "", 256, 0.0, {}, Complexity::Medium}});
    return cases;
}

const BaselineTolerance& toleranceFor(const BaselineCase& c) {
    auto found = baselineTolerances().find(c.stage);
    if (found == baselineTolerances().end())
        throw std::runtime_error("no baseline tolerance for " + c.stage + " in testRenderBaselines.cpp");
    return found->second;
}

fs::path outputPath(const std::string& file) {
    fs::path directory = fs::path(HDHAIR_BINARY_DIR) / "testenv-output";
    fs::create_directories(directory);
    return directory / file;
}

fs::path baselinePath(const std::string& file) { return fs::path(sourcePath("testenv/baselines")) / file; }

// A render as the files a user gets: written, then read back as stored.
struct WrittenRender {
    fs::path displayPath, linearPath;
    Image display, linear;
    void remove() const {
        fs::remove(displayPath);
        fs::remove(linearPath);
    }
};

WrittenRender writeRender(const Image& color, const std::string& name) {
    WrittenRender written{outputPath(name + ".png"), outputPath(name + ".exr"), {}, {}};
    writeImage(color, written.displayPath.string());
    writeImage(color, written.linearPath.string());
    written.display = readImage(written.displayPath.string());
    written.linear = readImage(written.linearPath.string());
    return written;
}

struct BaselineVerdict {
    ImageComparison display, linear;
    bool passed() const { return display.passed && linear.passed; }
    std::string describe() const { return "display " + display.description + "\n  linear " + linear.description; }
};

BaselineVerdict compareWithBaseline(const WrittenRender& render, const BaselineCase& c) {
    const BaselineTolerance& tolerance = toleranceFor(c);
    return {compareImages(render.display, readImage(baselinePath(c.name + ".png").string()), tolerance.display),
            compareImages(render.linear, readImage(baselinePath(c.name + ".exr").string()), tolerance.linear)};
}

class Baseline : public ::testing::TestWithParam<BaselineCase> {};

// Names the case in gtest's messages (instead of its bytes).
void PrintTo(const BaselineCase& c, std::ostream* out) { *out << c.name; }

}  // namespace

TEST_P(Baseline, MatchesCheckedInImages) {
    const BaselineCase& c = GetParam();
    StageRender render = renderStage(c.request);
    EXPECT_TRUE(render.warnings.empty()) << render.warnings.front().where << ": " << render.warnings.front().message;
    WrittenRender written = writeRender(render.result.color, c.name);
    if (updatingBaselines()) {
        fs::copy_file(written.displayPath, baselinePath(c.name + ".png"), fs::copy_options::overwrite_existing);
        fs::copy_file(written.linearPath, baselinePath(c.name + ".exr"), fs::copy_options::overwrite_existing);
        written.remove();
        HDHAIR_BASELINES_REWRITTEN(baselinePath(c.name + ".{png,exr}").string());
    }
    for (const char* extension : {".png", ".exr"})
        ASSERT_TRUE(fs::exists(baselinePath(c.name + extension)))
            << "no baseline " << baselinePath(c.name + extension) << " (create it with HDHAIR_UPDATE_BASELINES=1)";
    BaselineVerdict verdict = compareWithBaseline(written, c);
    EXPECT_TRUE(verdict.passed()) << c.name << ":\n  " << verdict.describe() << "\n  actual images: "
                                  << written.displayPath << ", " << written.linearPath;
    if (!HasFailure()) written.remove();
}

TEST_P(Baseline, MatchesWithTheCameraOneSubPixelStepAway) {
    const BaselineCase& c = GetParam();
    if (updatingBaselines()) FAIL() << "baselines are being rewritten: this run checks nothing";
    StageRenderRequest shifted = c.request;
    shifted.pixelShift = 1.0 / 256.0;
    WrittenRender written = writeRender(renderStage(shifted).result.color, c.name + ".shifted");
    BaselineVerdict verdict = compareWithBaseline(written, c);
    EXPECT_TRUE(verdict.passed()) << c.name << " moved by 1/256 px:\n  " << verdict.describe();
    std::printf("moved by 1/256 px:\n  %s\n", verdict.describe().c_str());
    if (!HasFailure()) written.remove();
}

TEST_P(Baseline, FailsForEveryDefectThatApplies) {
    const BaselineCase& c = GetParam();
    if (updatingBaselines()) FAIL() << "baselines are being rewritten: this run checks nothing";
    Diagnostics diagnostics;
    Scene scene = readStage(c.request, diagnostics);
    RenderResult baseline = renderScene(scene, c.request).result;
    CameraView camera = stageCamera(scene, c.request, sharedRenderer(), diagnostics);
    std::vector<BaselineDefect> defects = defectsThatApply(scene, c.request, baseline.plan, camera);
    // Every stage has lit strands: at least Kd, or a light, applies.
    ASSERT_FALSE(defects.empty()) << c.name << ": no defect applies, so its baselines guard nothing";
    for (const BaselineDefect& defect : defects) {
        DefectiveStage defective = withDefect(scene, c.request, defect);
        WrittenRender written = writeRender(renderScene(defective.scene, defective.request).result.color,
                                            c.name + ".defect");
        BaselineVerdict verdict = compareWithBaseline(written, c);
        EXPECT_FALSE(verdict.passed()) << c.name << " with " << defect.name
                                       << " still matches its baselines:\n  " << verdict.describe();
        std::printf("%s:\n  %s\n", defect.name.c_str(), verdict.describe().c_str());
        written.remove();
    }
}

INSTANTIATE_TEST_SUITE_P(Stages, Baseline, ::testing::ValuesIn(baselineCases()),
                         [](const ::testing::TestParamInfo<BaselineCase>& stage) { return stage.param.name; });

// Every stage file is in TestStages.h, so the parity test covers it and the
// baseline test renders it (or says why not, with baselineWidth 0). Layers
// that only serve a root stage (composition/, instancing/) are not stages.
TEST(Stages, EveryStageFileIsListed) {
    std::set<std::string> listed;
    for (const TestStage& stage : testStages()) listed.insert(stage.path);
    std::vector<std::string> files;
    for (const char* directory : {"examples", "testenv/stages"})
        for (const auto& entry : fs::directory_iterator(sourcePath(directory)))
            if (entry.path().extension() == ".usda")
                files.push_back(std::string(directory) + "/" + entry.path().filename().string());
    for (const auto& entry : fs::directory_iterator(sourcePath("testenv/stages")))
        if (entry.is_directory() && fs::exists(entry.path() / "root.usda"))
            files.push_back("testenv/stages/" + entry.path().filename().string() + "/root.usda");
    ASSERT_GE(files.size(), testStages().size());
    for (const std::string& file : files) EXPECT_TRUE(listed.count(file)) << file << " is not in TestStages.h";
    for (const std::string& path : listed) EXPECT_TRUE(fs::exists(sourcePath(path))) << path << " does not exist";
}

TEST(Rendering, EmptyStageRendersBackgroundOnly) {
    StageRender render = renderStage({"testenv/stages/empty.usda", "/World/main_cam", 128, 0.0, {}});
    // A whole frame (93 rows: usdrecord's rule for the 20.955 x 15.2908
    // aperture), not an empty image, holds only background.
    ASSERT_EQ(render.result.color.pixels.size(), size_t(128 * 93 * 4));
    ASSERT_EQ(render.result.depth.pixels.size(), size_t(128 * 93));
    for (float value : render.result.color.pixels) ASSERT_EQ(value, 0.0f);
    for (float depth : render.result.depth.pixels) ASSERT_EQ(depth, 1.0f);
}

TEST(Rendering, DoublingEveryWidthIncreasesCoveredPixels) {
    double thin = coverage(renderStage({"testenv/stages/widths.usda", "/World/main_cam", 256, 0.0, {}}).result.color);
    double thick =
        coverage(renderStage({"testenv/stages/widths_doubled.usda", "/World/main_cam", 256, 0.0, {}}).result.color);
    EXPECT_GT(thin, 0.0);
    // Ribbons twice as wide cover about twice the pixels; demand a clear increase.
    EXPECT_GT(thick, 1.5 * thin) << "thin " << thin << ", doubled " << thick;
}

TEST(Rendering, RenderedPixelsAreFiniteAndPremultiplied) {
    StageRender render = renderStage({"examples/dense_clump.usda", "/World/main_cam", 256, 0.0, {}});
    const Image& color = render.result.color;
    for (size_t p = 0; p < color.pixels.size(); p += 4) {
        for (int c = 0; c < 4; ++c) ASSERT_TRUE(std::isfinite(color.pixels[p + size_t(c)]));
        ASSERT_GE(color.pixels[p + 3], 0.0f);
        ASSERT_LE(color.pixels[p + 3], 1.0f);
        if (color.pixels[p + 3] == 0.0f) {
            ASSERT_EQ(color.pixels[p], 0.0f);
        }
    }
    EXPECT_GT(coverage(color), 0.02);
}

TEST(Rendering, AnimatedTransformMovesTheStrands) {
    Image start = renderStage({"testenv/stages/xforms.usda", "/World/main_cam", 128, 1.0, {}}).result.color;
    Image end = renderStage({"testenv/stages/xforms.usda", "/World/main_cam", 128, 10.0, {}}).result.color;
    // Only /World/animated moves: its three strands leave their pixels and
    // cover others, all of them far over 0.05 apart.
    ImageComparison comparison = compareImages(end, start, exactWithin(0.05));
    EXPECT_GT(comparison.outliers, 40u) << comparison.description;
    EXPECT_LT(comparison.outliers, comparison.coveredPixels / 4) << "only one of eight groups moves";
}

TEST(Rendering, EglAndOsMesaMatchTheSameBaseline) {
    // Two GL front ends over the same rasteriser: what differs between them
    // must stay within a baseline's tolerance, like another CPU's rounding.
    for (const BaselineCase& c : baselineCases()) {
        if (c.name != "straight_strands") continue;
        WrittenRender written =
            writeRender(renderStage(c.request, gl::GlBackend::OsMesa).result.color, c.name + ".osmesa");
        BaselineVerdict verdict = compareWithBaseline(written, c);
        EXPECT_TRUE(verdict.passed()) << verdict.describe();
        written.remove();
        return;
    }
    FAIL() << "no straight_strands baseline case";
}

TEST(Rendering, HigherComplexityTessellatesMoreFinelyButLooksAlike) {
    StageRenderRequest coarse{"examples/wavy_strands.usda", "/World/main_cam", 256, 0.0, {"maxSegmentsPerSpan=1"}};
    StageRenderRequest fine{"examples/wavy_strands.usda", "/World/main_cam", 256, 0.0,
                            {"maxSegmentsPerSpan=32", "tessellationTolerance=0.05"}};
    Image a = renderStage(coarse).result.color, b = renderStage(fine).result.color;
    // One segment per span visibly straightens the waves: many covered
    // pixels change. The strands stay where they were, about as wide: about
    // as many pixels are covered (measured 0.89 as many: chords are shorter
    // than the waves they cut).
    ImageComparison comparison = compareImages(a, b, exactWithin(0.05));
    EXPECT_GT(double(comparison.outliers), 0.05 * double(comparison.coveredPixels)) << comparison.description;
    EXPECT_NEAR(coverage(a) / coverage(b), 1.0, 0.2) << "coarse " << coverage(a) << ", fine " << coverage(b);
}

TEST(Rendering, DenseStrandsAtHighTessellationStayIntact) {
    // llvmpipe corrupts draws whose tessellation emits too many vertices
    // (hdHair/gl/PatchBatching.h): spikes add coverage. Finer tessellation of
    // the same strands must cover the same pixels, give or take edges.
    auto coverageAt = [](const char* level) {
        return coverage(renderStage({"examples/dense_clump.usda", "/World/main_cam", 256, 0.0,
                                     {"tessellation=projectedLength", "pixelsPerSegment=0.25", std::string("maxSegmentsPerSpan=") + level}})
                            .result.color);
    };
    double moderate = coverageAt("12"), fine = coverageAt("32");
    EXPECT_NEAR(fine, moderate, 0.03 * moderate) << "12 segments/span: " << moderate << ", 32: " << fine;
}

TEST(Rendering, SceneEditsBetweenFramesShowUpInTheNextFrame) {
    // Hydra edits the scene one prim at a time between frames; the renderer's
    // caches must follow: a changed prim is re-prepared, a removed one disappears.
    Diagnostics diagnostics;
    Scene scene;
    usda::readSceneFile(sourcePath("testenv/stages/widths.usda"), 0.0, scene, diagnostics);
    Renderer& renderer = sharedRenderer();
    CameraView camera = cameraViewFromPrim(*scene.findCamera("/World/main_cam"), 128);
    RenderSettings settings;
    double before = coverage(renderer.render(scene, camera, settings, diagnostics).color);
    ASSERT_GT(before, 0.0);

    std::string path = scene.curves().begin()->first;
    CurvesPrim wider = *scene.curves().begin()->second.prim;
    for (float& width : wider.primvars.at("widths").values) width *= 3.0f;
    scene.setCurves(wider);
    double widened = coverage(renderer.render(scene, camera, settings, diagnostics).color);
    EXPECT_GT(widened, before * 1.5);

    for (const auto& [curvesPath, entry] : Scene::Entries<CurvesPrim>(scene.curves())) scene.remove(curvesPath);
    EXPECT_EQ(coverage(renderer.render(scene, camera, settings, diagnostics).color), 0.0);
    EXPECT_TRUE(diagnostics.warnings().empty());
}
