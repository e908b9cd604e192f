// Every case folder under testenv/cases rendered with hdhair-record and
// compared with its baseline through the case's OCIO display transform
// (TestCases.h). HDHAIR_UPDATE_BASELINES=1 rewrites the baselines instead, and fails (BaselineUpdates.h).

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>

#include <gtest/gtest.h>

#include "StageRendering.h"
#include "TestCases.h"
#include "hdHair/image/ImageWriter.h"
#include "hdHair/base/FrameSpec.h"
#include "testenv/tests/BaselineUpdates.h"

using namespace hdhair;
using namespace hdhair::testenv;
namespace fs = std::filesystem;

namespace {

// A fresh folder for one case's outputs in the build tree.
std::string outputFolderFor(const std::string& name) {
    const fs::path folder = fs::path(HDHAIR_BINARY_DIR) / "testenv-cases" / name;
    fs::remove_all(folder);
    fs::create_directories(folder);
    return folder.string();
}

class Cases : public ::testing::TestWithParam<std::string> {};

TEST_P(Cases, MatchItsBaselineThroughItsDisplayTransform) {
    const TestCase testCase = loadTestCase(GetParam());
    const std::string output = outputFolderFor(testCase.name);
    std::string log;
    ASSERT_EQ(renderCase(testCase, output, &log), 0) << log;
    const std::vector<std::string> actual = frameFiles(testCase, output, "actual");
    const std::vector<std::string> baselines = frameFiles(testCase, testCase.folder, "baseline");
    ASSERT_EQ(actual.size(), baselines.size());
    for (size_t frame = 0; frame < actual.size(); ++frame) {
        ASSERT_TRUE(fs::exists(actual[frame])) << actual[frame] << " was not written:\n" << log;
        if (updatingBaselines()) {
            updateBaseline(testCase, actual[frame], baselines[frame]);
            std::cout << "updated " << baselines[frame] << " and its .png\n";
            if (frame + 1 == actual.size()) HDHAIR_BASELINES_REWRITTEN(testCase.name);
            continue;
        }
        const CaseVerdict verdict = compareWithBaseline(testCase, actual[frame], baselines[frame], output);
        std::cout << verdict.report << "\n";
        EXPECT_TRUE(verdict.passed) << testCase.description << "\n" << verdict.report;
        // The reviewed picture is the baseline's own display image, not a
        // stale one left from an earlier baseline.
        const std::string png = fs::path(baselines[frame]).replace_extension(".png").string();
        ASSERT_TRUE(fs::exists(png)) << png;
        // 8 bits hold [0, 1]: a look may push the display image past 1.
        Image shown = caseDisplayImage(testCase, baselines[frame]);
        for (float& value : shown.pixels) value = std::clamp(value, 0.0f, 1.0f);
        const ImageComparison current = compareImages(readImage(png), shown, exactWithin(1.0 / 255.0));
        EXPECT_TRUE(current.passed) << png << " is not the display image of its EXR: " << current.description;
    }
}

std::string caseName(const ::testing::TestParamInfo<std::string>& info) { return caseTestName(info.param); }

INSTANTIATE_TEST_SUITE_P(Testenv, Cases, ::testing::ValuesIn(testCaseFolders()), caseName);

class CaseMutations : public ::testing::TestWithParam<std::string> {};

// The case's hdhair-record arguments (the ones cases use: --camera, -w,
// --complexity, -s) as an in-process request, at its first frame.
StageRenderRequest inProcessRequest(const TestCase& testCase) {
    StageRenderRequest request;
    request.stagePath = testCase.stage;
    request.time = testCase.frames.empty() ? -std::numeric_limits<double>::infinity()
                                           : parseFrameSpec(testCase.frames).front();
    for (size_t i = 0; i + 1 < testCase.arguments.size(); i += 2) {
        const std::string& option = testCase.arguments[i];
        const std::string& value = testCase.arguments[i + 1];
        if (option == "--camera") request.camera = value;
        else if (option == "-w") request.imageWidth = std::stoi(value);
        else if (option == "-s") request.settings.push_back(value);
        else if (option == "--complexity") {
            EXPECT_TRUE(parseToken(value, &request.complexity)) << value;
        } else {
            ADD_FAILURE() << testCase.name << ": no in-process form of " << option;
        }
    }
    return request;
}

// The scene with `edit` made (StageEdit); false when nothing in it applies.
bool editScene(Scene& scene, StageEdit edit) {
    std::vector<CurvesPrim> edited;
    if (edit == StageEdit::DropStrand) {
        const CurvesPrim* most = nullptr;
        for (const auto& [path, entry] : scene.curves())
            if (!most || entry.prim->curveVertexCounts.size() > most->curveVertexCounts.size()) most = entry.prim.get();
        if (!most || most->curveVertexCounts.size() < 2) return false;
        CurvesPrim prim = *most;
        prim.invisibleCurves.push_back(int(prim.curveVertexCounts.size() / 2));
        edited.push_back(std::move(prim));
    } else {
        for (const auto& [path, entry] : scene.curves()) {
            if (!entry.prim->findPrimvar("widths")) continue;
            CurvesPrim prim = *entry.prim;
            for (float& width : prim.primvars.at("widths").values) width *= 1.5f;
            edited.push_back(std::move(prim));
        }
    }
    for (CurvesPrim& prim : edited) scene.setCurves(std::move(prim));
    return !edited.empty();
}

// Renders the case in this process, its stage edited, to `exrPath` as
// hdhair-record writes it (linear, its rendering space in the metadata).
void renderEdited(const TestCase& testCase, StageEdit edit, const std::string& exrPath) {
    const StageRenderRequest request = inProcessRequest(testCase);
    Diagnostics diagnostics;
    Scene scene = readStage(request, diagnostics);
    if (edit != StageEdit::None) {
        ASSERT_TRUE(editScene(scene, edit)) << testCase.name << ": nothing to edit";
    }
    const StageRender render = renderScene(scene, request);
    ImageColor color;
    color.space = stageSettings(request).renderingSpace();
    writeImage(render.result.color, exrPath, color);
}

// A case is only as good as the defects it catches: each declares, in its
// case.json, the relevant settings and views (TestCases.h, caseMutation)
// whose change must make it fail against its baseline: sorting on blended
// hair, shadows where lit, the other shading model, another display view.
// A mutation that passes is a defect the case would not see.
TEST_P(CaseMutations, EachDeclaredMutationFailsAgainstTheBaseline) {
    const TestCase testCase = loadTestCase(GetParam());
    ASSERT_FALSE(testCase.mutations.empty()) << testCase.folder << "/case.json declares no \"mutations\"";
    const std::string baseline = frameFiles(testCase, testCase.folder, "baseline").front();
    bool renderedInProcess = false;
    for (const std::string& name : testCase.mutations) {
        SCOPED_TRACE(name);
        const CaseMutation mutation = caseMutation(name);
        TestCase mutated = testCase;
        if (mutation.edit != StageEdit::None) {
            const std::string output = outputFolderFor(testCase.name + ".mutated-" + name);
            // The in-process render, unedited, must match: else an edit
            // that fails would prove nothing.
            if (!renderedInProcess) {
                renderedInProcess = true;
                const std::string plain = output + "/unedited.exr";
                renderEdited(testCase, StageEdit::None, plain);
                const CaseVerdict verdict = compareWithBaseline(testCase, plain, baseline, output);
                ASSERT_TRUE(verdict.passed) << "rendered in process, " << testCase.name
                                            << " does not match its baseline:\n" << verdict.report;
            }
            const std::string actual = output + "/actual.exr";
            renderEdited(testCase, mutation.edit, actual);
            const CaseVerdict verdict = compareWithBaseline(testCase, actual, baseline, output);
            EXPECT_FALSE(verdict.passed) << testCase.name << " still matches its baseline with " << name
                                         << ": it would not catch that defect\n"
                                         << verdict.report;
            continue;
        }
        if (!mutation.view.empty()) {
            // The reviewed PNG is the baseline through the case's view; another
            // view must not reproduce it.
            mutated.display.view = mutation.view;
            Image shown = caseDisplayImage(mutated, baseline);
            for (float& value : shown.pixels) value = std::clamp(value, 0.0f, 1.0f);
            const std::string png = fs::path(baseline).replace_extension(".png").string();
            const ImageComparison same = compareImages(readImage(png), shown, exactWithin(1.0 / 255.0));
            EXPECT_FALSE(same.passed) << testCase.name << " shows the same through the " << mutation.view << " view";
            continue;
        }
        mutated.arguments.insert(mutated.arguments.end(), mutation.arguments.begin(), mutation.arguments.end());
        const std::string output = outputFolderFor(testCase.name + ".mutated-" + name);
        std::string log;
        ASSERT_EQ(renderCase(mutated, output, &log), 0) << log;
        const CaseVerdict verdict =
            compareWithBaseline(testCase, frameFiles(mutated, output, "actual").front(), baseline, output);
        EXPECT_FALSE(verdict.passed) << testCase.name << " still matches its baseline with " << name
                                     << ": it would not catch that defect\n"
                                     << verdict.report;
    }
}

INSTANTIATE_TEST_SUITE_P(Testenv, CaseMutations, ::testing::ValuesIn(testCaseFolders()), caseName);

// A render that no longer matches must fail with a report a person can act
// on: the statistics, and the actual and difference images written.
TEST(CaseReport, APerturbedRenderFailsWithStatisticsAndImages) {
    const TestCase testCase = loadTestCase(sourcePath("testenv/cases/shading_kajiyakay"));
    const std::string output = outputFolderFor("perturbed");
    std::string log;
    ASSERT_EQ(renderCase(testCase, output, &log), 0) << log;
    const std::string actualExr = frameFiles(testCase, output, "actual").front();
    Image image = readImage(actualExr);
    // A band of rows a fifth of the image high, 20 % darker.
    for (int y = image.height / 2; y < image.height / 2 + image.height / 5; ++y)
        for (int x = 0; x < image.width; ++x)
            for (int c = 0; c < 3; ++c) image.pixels[4 * (size_t(y) * size_t(image.width) + size_t(x)) + size_t(c)] *= 0.8f;
    RenderingSpace space = RenderingSpace::LinearRec709;
    ASSERT_TRUE(parseToken(colorSpaceOf(actualExr), &space));
    writeImage(image, actualExr, {space, nullptr, nullptr});

    const CaseVerdict verdict =
        compareWithBaseline(testCase, actualExr, frameFiles(testCase, testCase.folder, "baseline").front(), output);
    std::cout << verdict.report << "\n";
    EXPECT_FALSE(verdict.passed);
    for (const char* part : {"shading_kajiyakay", "OUT OF TOLERANCE", "covered pixels", "worst (", "RMSE",
                             "shading_kajiyakay.actual.png", "shading_kajiyakay.difference.png"})
        EXPECT_NE(verdict.report.find(part), std::string::npos) << part << " in:\n" << verdict.report;
    for (const char* file : {"shading_kajiyakay.actual.png", "shading_kajiyakay.expected.png",
                             "shading_kajiyakay.difference.png"})
        EXPECT_TRUE(fs::exists(fs::path(output) / file)) << file;
    // The difference image shows the band and nothing else.
    const Image difference = readImage((fs::path(output) / "shading_kajiyakay.difference.png").string());
    const Image expected = readImage((fs::path(output) / "shading_kajiyakay.expected.png").string());
    double inside = 0.0, outside = 0.0;
    for (int y = 0; y < difference.height; ++y)
        for (int x = 0; x < difference.width; ++x) {
            const size_t p = 4 * (size_t(y) * size_t(difference.width) + size_t(x));
            if (expected.pixels[p + 3] < 0.5f) continue;
            const bool inBand = y >= image.height / 2 && y < image.height / 2 + image.height / 5;
            (inBand ? inside : outside) = std::max(inBand ? inside : outside, double(difference.pixels[p]));
        }
    EXPECT_GT(inside, 0.1);
    EXPECT_LT(outside, 0.05);
}

TEST(CaseReport, AMalformedCaseNamesItsFileAndKey) {
    const fs::path folder = fs::path(outputFolderFor("malformed"));
    std::ofstream(folder / "case.json") << R"({"description": "x", "stage": "../../nowhere.usda"})";
    try {
        loadTestCase(folder.string());
        FAIL() << "accepted";
    } catch (const std::runtime_error& error) {
        EXPECT_NE(std::string(error.what()).find("case.json"), std::string::npos) << error.what();
        EXPECT_NE(std::string(error.what()).find("does not exist"), std::string::npos) << error.what();
    }
    std::ofstream(folder / "case.json", std::ios::trunc)
        << R"({"description": "x", "stage": ")" << sourcePath("examples/wavy_strands.usda") << R"(", "arguments": [],)"
        << R"( "display": {}, "thresholds": {"fail": 0.01, "failpercent": 1}})";
    try {
        loadTestCase(folder.string());
        FAIL() << "accepted";
    } catch (const std::runtime_error& error) {
        EXPECT_NE(std::string(error.what()).find("missing \"hardfail\""), std::string::npos) << error.what();
    }
}

}  // namespace
