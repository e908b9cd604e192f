// One catalogue, two readers (docs/hard-cases.md, "Stages and command lines
// through both readers"): every hostile stage and command line here runs
// through hdhair-record with --reader embedded and, in a build with OpenUSD,
// --reader usd, and must get the same verdict from both:
// - an error: exit status 1, one line "hdhair-record: error: ..." holding the
//   case's text, and nothing left behind in the case's folder;
// - a picture: exit status 0, a finite EXR, and a warning holding the case's
//   text when the input was repaired.
// Where the two readers legitimately word a verdict differently (OpenUSD's
// own parser and composition errors), the case holds both texts and the
// catalogue says why.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "hdHair/image/ImageWriter.h"
#include "testenv/tests/BadInputStages.h"
#include "testenv/tests/Commands.h"

namespace hdhair::testenv {
namespace {

namespace fs = std::filesystem;

struct VerdictCase {
    std::string name;
    // The case's files, written into its own folder: the first is the stage
    // unless `stage` names one. "@DIR@" in a file or in `arguments` is the folder.
    std::vector<std::pair<std::string, std::string>> files;
    std::string arguments;     // before the stage and the output
    bool fails = false;        // an error, else a picture
    std::string said;          // the error line, or a warning, holds this
    std::string saidThroughUsd = std::string();  // what --reader usd says instead, when set
    std::string stage = std::string();           // the stage argument, when not the first file
    std::string output = "out.exr";              // in the case's folder
    int failsThroughUsd = -1;  // 0 or 1 where the readers' verdicts differ (the catalogue says why); -1: `fails`
};

// A camera /cam looking down -Z at two horizontal strands; `camera` and
// `hair` are extra lines inside the two prims.
std::string curvesStage(const std::string& hair, const std::string& camera = std::string(),
                        const std::string& header = "#usda 1.0") {
    return header + R"(
def Camera "cam" {
    float horizontalAperture = 20
    float verticalAperture = 20
    double3 xformOp:translate = (0, 0, 10)
    uniform token[] xformOpOrder = ["xformOp:translate"]
)" + camera + R"(
}
def BasisCurves "hair" {
    uniform token type = "linear"
    int[] curveVertexCounts = [2, 2]
    point3f[] points = [(-1, 0, 0), (1, 0, 0), (-1, 0.5, 0), (1, 0.5, 0)]
    float[] widths = [0.1] (interpolation = "constant")
)" + hair + "\n}\n";
}

// A prim /root with `arc` as its references (or payload), and nothing else.
std::string referencingStage(const std::string& arc, const std::string& kind = "references") {
    return "#usda 1.0\ndef Xform \"root\" (\n    " + kind + " = " + arc + "\n) {\n}\n";
}

const std::string kLayerWithDefault = "#usda 1.0\n(\n    defaultPrim = \"asset\"\n)\ndef Xform \"asset\" {\n}\n";

// `levels` layers, each of whose default prim references the next twice: the
// stage composes 2^levels prims ("billion laughs").
std::vector<std::pair<std::string, std::string>> doublingChain(int levels) {
    std::vector<std::pair<std::string, std::string>> files;
    for (int i = 0; i <= levels; ++i) {
        std::string text = "#usda 1.0\n(\n    defaultPrim = \"r\"\n)\ndef Xform \"r\" {\n";
        if (i < levels) {
            const std::string next = "@laugh" + std::to_string(i + 1) + ".usda@";
            text += "    def Xform \"a\" (references = " + next + ") {}\n    def Xform \"b\" (references = " + next +
                    ") {}\n";
        }
        files.emplace_back("laugh" + std::to_string(i) + ".usda", text + "}\n");
    }
    return files;
}

// The same in one layer, through internal references.
std::string internalDoublingChain(int levels) {
    std::string text = "#usda 1.0\ndef Xform \"p0\" {\n}\n";
    for (int i = 1; i <= levels; ++i) {
        const std::string previous = "</p" + std::to_string(i - 1) + ">";
        text += "def Xform \"p" + std::to_string(i) + "\" {\n    def Xform \"a\" (references = " + previous +
                ") {}\n    def Xform \"b\" (references = " + previous + ") {}\n}\n";
    }
    return text;
}

std::string deeplyNested(int levels) {
    std::string text = "#usda 1.0\n";
    for (int i = 0; i < levels; ++i) text += "def Xform \"p" + std::to_string(i) + "\" {\n";
    for (int i = 0; i < levels; ++i) text += "}\n";
    return text;
}

std::vector<VerdictCase> catalogue() {
    const std::string camera = "--camera /cam ";
    auto stage = [](const std::string& text) { return std::vector<std::pair<std::string, std::string>>{{"stage.usda", text}}; };
    std::vector<VerdictCase> cases = {
        // Syntax: the file and line, from either parser.
        {"truncatedArray", stage("#usda 1.0\ndef BasisCurves \"hair\" {\n    int[] curveVertexCounts = [2\n"), "", true,
         "stage.usda:4:"},
        {"unbalancedBracket", stage("#usda 1.0\ndef BasisCurves \"hair\" {\n    int[] curveVertexCounts = [2\n}\n"), "",
         true, "stage.usda:4:"},
        {"unterminatedString", stage("#usda 1.0\ndef BasisCurves \"hair\" {\n    uniform token type = \"linear\n}\n"),
         "", true, "stage.usda:3:"},
        {"newerUsdaVersion", stage(curvesStage("", "", "#usda 2.0")), "", true,
         "stage.usda:1:7: unsupported usda version '2.0' (expected '1.0')"},
        {"noHeader", stage("def Xform \"root\" {\n}\n"), "", true, "stage.usda:1:",
         "stage.usda: OpenUSD cannot open it"},
        {"emptyFile", stage(""), "", true, "stage.usda:1:", "stage.usda: OpenUSD cannot open it"},
        {"binaryGarbage", stage("#usda 1.0\n\x01\x02\xff\xfe garbage\n"), "", true, "stage.usda:2:"},
        {"deepNesting", stage(deeplyNested(5000)), "", true, "stage.usda:202:1: nesting deeper than 200 levels",
         "stage.usda:188: memory exhausted"},
        {"byteOrderMark", stage("\xEF\xBB\xBF" + curvesStage("")), camera, false, "",
         "stage.usda: OpenUSD cannot open it: </", "", "out.exr", 1},
        {"nulInAToken",
         stage(curvesStage(std::string("    uniform token basis = \"bez") + '\0' + "ier\"")), camera, false,
         "/hair.basis: unknown curve basis 'bez\\x00ier'; using bezier"},
        {"stageIsADirectory", {}, "", true, "a directory, not a regular file", "", "@DIR@"},
        {"stageIsADevice", {}, "", true, "a character device, not a regular file", "", "/dev/zero"},
        {"stageMissing", {}, "", true, "No such file or directory", "", "@DIR@/missing.usda"},

        // Cameras: one verdict, naming the prim and attribute.
        {"zeroFocalLength", stage(curvesStage("", "    float focalLength = 0")), camera, true,
         "/cam.focalLength: 0 is not a positive length; the camera cannot be used"},
        {"nanFocalLength", stage(curvesStage("", "    float focalLength = nan")), camera, true,
         "/cam.focalLength: nan is not a number"},
        {"infiniteFocalLength", stage(curvesStage("", "    float focalLength = inf")), camera, true,
         "/cam.focalLength: inf is not a number"},
        {"negativeAperture", stage(curvesStage("", "    float horizontalAperture = -20")), camera, true,
         "/cam.horizontalAperture: -20 is not a positive length"},
        {"zeroVerticalAperture", stage(curvesStage("", "    float verticalAperture = 0")), camera, true,
         "/cam.verticalAperture: 0 is not a positive length"},
        {"nanApertureOffset", stage(curvesStage("", "    float horizontalApertureOffset = nan")), camera, true,
         "/cam.horizontalApertureOffset: nan is not a number"},
        {"zeroOrthographicAperture",
         stage(curvesStage("", "    token projection = \"orthographic\"\n    float horizontalAperture = 0")), camera,
         true, "/cam.horizontalAperture: 0 is not a positive length"},
        {"nanCameraTransform",
         stage(curvesStage("", "    double3 xformOp:rotateXYZ = (nan, 0, 0)\n    uniform token[] xformOpOrder = "
                               "[\"xformOp:translate\", \"xformOp:rotateXYZ\"]")),
         camera, true, "/cam: the world transform is not finite"},
        {"singularCameraTransform",
         stage(curvesStage("", "    float3 xformOp:scale = (0, 1, 1)\n    uniform token[] xformOpOrder = "
                               "[\"xformOp:translate\", \"!invert!xformOp:scale\"]")),
         camera, true, "/cam: the world transform is not finite"},
        {"zeroNearPlane", stage(curvesStage("", "    float2 clippingRange = (0, 100)")), camera, false,
         "/cam.clippingRange: (0, 100) is a near distance that is not positive; using USD's fallback (1, 1000000)"},
        {"equalClippingPlanes", stage(curvesStage("", "    float2 clippingRange = (5, 5)")), camera, false,
         "/cam.clippingRange: (5, 5) is far not beyond near"},
        {"invertedClippingPlanes", stage(curvesStage("", "    float2 clippingRange = (5, 1)")), camera, false,
         "/cam.clippingRange: (5, 1) is far not beyond near"},
        {"negativeNearPlane", stage(curvesStage("", "    float2 clippingRange = (-1, 100)")), camera, false,
         "/cam.clippingRange: (-1, 100) is a near distance that is not positive"},
        {"nanClippingPlane", stage(curvesStage("", "    float2 clippingRange = (nan, 100)")), camera, false,
         "/cam.clippingRange: (nan, 100) is not finite"},
        {"wideApertureRatio", stage(curvesStage("", "    float verticalAperture = 0.002")), camera, false,
         "/cam.horizontalAperture, /cam.verticalAperture: (20, 0.002) make an image 1e+04 times as wide as it is tall"},
        {"tallApertureRatio", stage(curvesStage("", "    float horizontalAperture = 0.1")), camera, false,
         "/cam.horizontalAperture, /cam.verticalAperture: (0.1, 20) make an image 0.005 times as wide"},
        {"missingCamera", stage(curvesStage("")), "--camera /nowhere ", true, "no camera at '/nowhere'"},
        {"cameraPathIsNotACamera", stage(curvesStage("")), "--camera /hair ", true, "no camera at '/hair'"},

        // Composition: an error naming the arc, in either reader.
        {"missingSublayer", stage("#usda 1.0\n(\n    subLayers = [@missing.usda@]\n)\n" + curvesStage("").substr(10)),
         "", true, "stage.usda:3:", "stage.usda: composition error: Could not load sublayer @missing.usda@"},
        {"missingReference", stage(referencingStage("@missing.usda@")), "", true,
         "cannot open referenced layer '@DIR@/missing.usda': No such file or directory",
         "stage.usda: composition error: Could not open asset @missing.usda@ for reference"},
        {"missingPayload", stage(referencingStage("@missing.usda@", "payload")), "", true,
         "cannot open payload layer '@DIR@/missing.usda': No such file or directory",
         "stage.usda: composition error: Could not open asset @missing.usda@ for payload"},
        {"referenceToADirectory", stage(referencingStage("@/tmp@")), "", true, "a directory, not a regular file"},
        {"referenceToADevice", stage(referencingStage("@/dev/zero@")), "", true,
         "a character device, not a regular file"},
        {"referenceToPasswd", stage(referencingStage("@/etc/passwd@")), "", true,
         "/etc/passwd:1:1: expected the '#usda 1.0' header",
         "/etc/passwd: OpenUSD cannot open it: Cannot determine file format for @/etc/passwd@"},
        {"referenceWithoutDefaultPrim",
         {{"stage.usda", referencingStage("@asset.usda@")}, {"asset.usda", "#usda 1.0\ndef Xform \"asset\" {\n}\n"}},
         "", true, "has no defaultPrim, so the reference must name a prim",
         "stage.usda: composition error: Unresolved reference prim path @@DIR@/asset.usda@<defaultPrim>"},
        {"referenceToAMissingPrim",
         {{"stage.usda", referencingStage("@asset.usda@</nowhere>")}, {"asset.usda", kLayerWithDefault}}, "", true,
         "referenced prim </nowhere> does not exist in",
         "stage.usda: composition error: Unresolved reference prim path @@DIR@/asset.usda@</nowhere>"},
        {"referenceCycle",
         {{"stage.usda", referencingStage("@a.usda@")},
          {"a.usda", "#usda 1.0\n(\n    defaultPrim = \"a\"\n)\ndef Xform \"a\" (\n    references = @b.usda@\n) {\n}\n"},
          {"b.usda", "#usda 1.0\n(\n    defaultPrim = \"b\"\n)\ndef Xform \"b\" (\n    references = @a.usda@\n) {\n}\n"}},
         "", true, "reference cycle", "stage.usda: composition error: Cycle detected"},
        {"sublayerCycle",
         {{"stage.usda", "#usda 1.0\n(\n    subLayers = [@other.usda@]\n)\n"},
          {"other.usda", "#usda 1.0\n(\n    subLayers = [@stage.usda@]\n)\n"}},
         "", true, "sublayer cycle", "stage.usda: composition error: Sublayer hierarchy with root layer"},
        {"doublingReferenceChain", doublingChain(40), "", true,
         "the stage composes more than 5000000 prims, the most hdHair reads"},
        {"internalDoublingChain", stage(internalDoublingChain(40)), "", true,
         "the stage composes more than 5000000 prims, the most hdHair reads"},

        // Values: repaired, with a warning naming the prim and attribute.
        {"nanDisplayColor",
         stage(curvesStage("    color3f[] primvars:displayColor = [(nan, 0.5, 0.5)] (interpolation = \"constant\")")),
         camera, false, "/hair.primvars:displayColor: 1 element is not finite (first: element 0); using the fallback"},
        {"nanDisplayOpacity",
         stage(curvesStage("    float[] primvars:displayOpacity = [nan] (interpolation = \"constant\")")), camera,
         false, "/hair.primvars:displayOpacity: 1 element is not finite (first: element 0); using the fallback 1"},
        {"infiniteWidths", stage(curvesStage("    float[] primvars:widths = [inf] (interpolation = \"constant\")")),
         camera, false, "/hair.widths: 1 element is not finite (first: element 0); using the fallback 1"},
        {"pointAt1e38",
         stage(curvesStage("    point3f[] points = [(-1, 0, 0), (1, 0, 0), (-1, 0.5, 0), (1e38, 0.5, 0)]")),
         camera, false, "/hair.points: curve 1 has a point past 1e+18 (points[3] = (1e+38, 0.5, 0))"},
        {"nanPoint", stage(curvesStage("    point3f[] points = [(-1, 0, 0), (1, 0, 0), (-1, nan, 0), (1, 0.5, 0)]")),
         camera, false, "/hair.points: curve 1 has a non-finite point (points[2]); dropping the curve"},
        {"unknownInterpolation",
         stage(curvesStage("    color3f[] primvars:displayColor = [(1, 0.5, 0.5)] (interpolation = \"bogus\")")),
         camera, false, "/hair.primvars:displayColor: unknown interpolation 'bogus'; using constant"},
        {"zeroElementSize",
         stage(curvesStage("    color3f[] primvars:displayColor = [(1, 0.5, 0.5)] (\n        interpolation = "
                           "\"constant\"\n        elementSize = 0\n    )")),
         camera, false, "/hair.primvars:displayColor: elementSize must be a positive integer; using 1"},
        {"negativeElementSize",
         stage(curvesStage("    color3f[] primvars:displayColor = [(1, 0.5, 0.5)] (\n        interpolation = "
                           "\"constant\"\n        elementSize = -3\n    )")),
         camera, false, "/hair.primvars:displayColor: elementSize must be a positive integer; using 1"},
        {"hugeElementSize",
         stage(curvesStage("    color3f[] primvars:displayColor = [(1, 0.5, 0.5)] (\n        interpolation = "
                           "\"constant\"\n        elementSize = 1000000000\n    )")),
         camera, false, "/hair.primvars:displayColor: elementSize must be a positive integer; using 1"},
        {"unknownBasis", stage(curvesStage("    uniform token basis = \"bogus\"")), camera, false,
         "/hair.basis: unknown curve basis 'bogus'; using bezier"},
        {"unknownCurveType", stage(curvesStage("    uniform token type = \"bogus\"")), camera, false,
         "/hair.type: unknown curve type 'bogus'; using cubic"},
        {"unknownWrap", stage(curvesStage("    uniform token wrap = \"bogus\"")), camera, false,
         "/hair.wrap: unknown curve wrap 'bogus'; using nonperiodic"},
        {"negativeWidths", stage(curvesStage("    float[] primvars:widths = [-0.5] (interpolation = \"constant\")")),
         camera, false, "/hair.widths:"},
        {"wrongColorCount",
         stage(curvesStage("    color3f[] primvars:displayColor = [(1, 0, 0), (0, 1, 0), (0, 0, 1)] (interpolation = "
                           "\"vertex\")")),
         camera, false, "/hair.primvars:displayColor: vertex interpolation needs 4 values, found 3"},

        // Command lines: refused before anything is rendered, and a run that
        // fails part way leaves nothing behind.
        {"emptyFrameSpec", stage(curvesStage("")), "--frames '' ", true, "bad frame spec '': no frames"},
        {"malformedFrameSpec", stage(curvesStage("")), "--frames 1,x ", true, "bad frame spec '1,x'"},
        {"brokenCameraAtTheSecondFrame",
         stage(curvesStage("", "    float focalLength.timeSamples = {\n        1: 50,\n        2: 0,\n    }")),
         camera + "--frames 1:2 ", true, "/cam.focalLength: 0 is not a positive length", "", "", "out.#.exr"},
        {"statsThatCannotBeWritten", stage(curvesStage("")), camera + "--stats /proc/hdhair-stats.json ", true,
         "/proc/hdhair-stats.json"},
    };
    // Bad lights, transforms and materials (BadInputStages.h), which
    // testHardCases also renders in process to check every AOV.
    for (const InputCase& input : kBadInputs)
        cases.push_back({std::string("badInput_") + input.name, stage(stageText(input.hair, input.extra)), camera, false,
                         input.warning});
    return cases;
}

std::string replacedAll(std::string text, const std::string& from, const std::string& to) {
    for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
        text.replace(at, from.size(), to);
    return text;
}

int lineCount(const std::string& text) { return int(std::count(text.begin(), text.end(), '\n')); }

struct Verdict {
    VerdictCase input;
    std::string reader;
};

void PrintTo(const Verdict& verdict, std::ostream* out) { *out << verdict.input.name << " " << verdict.reader; }

class ReaderVerdicts : public ::testing::TestWithParam<Verdict> {};

TEST_P(ReaderVerdicts, AreTheCataloguesThroughBothReaders) {
    const VerdictCase& input = GetParam().input;
    const std::string& reader = GetParam().reader;
    const fs::path folder = fs::temp_directory_path() / "hdhair-reader-verdicts" / (input.name + "-" + reader);
    fs::remove_all(folder);
    fs::create_directories(folder);
    std::vector<fs::path> inputs;
    for (const auto& [name, text] : input.files) {
        std::ofstream(folder / name, std::ios::binary) << replacedAll(text, "@DIR@", folder.string());
        inputs.push_back(folder / name);
    }
    const std::string stagePath = input.stage.empty() ? inputs.front().string()
                                                       : replacedAll(input.stage, "@DIR@", folder.string());
    std::string output;
    const int status = runCommand(std::string(HDHAIR_RECORD) + " --reader " + reader + " -w 32 " +
                                      replacedAll(input.arguments, "@DIR@", folder.string()) + shellQuoted(stagePath) +
                                      " " + shellQuoted((folder / input.output).string()),
                                  &output);
    const std::string said = replacedAll(
        reader == "usd" && !input.saidThroughUsd.empty() ? input.saidThroughUsd : input.said, "@DIR@", folder.string());
    std::vector<fs::path> left;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder))
        if (std::find(inputs.begin(), inputs.end(), entry.path()) == inputs.end()) left.push_back(entry.path());
    const bool fails = reader == "usd" && input.failsThroughUsd >= 0 ? input.failsThroughUsd == 1 : input.fails;
    if (fails) {
        EXPECT_EQ(status, 1) << output;
        EXPECT_EQ(lineCount(output), 1) << output;
        EXPECT_EQ(output.rfind("hdhair-record: error: ", 0), 0u) << output;
        EXPECT_NE(output.find(said), std::string::npos) << "expected '" << said << "' in:\n" << output;
        EXPECT_TRUE(left.empty()) << "a failed run left " << left.front();
        return;
    }
    EXPECT_EQ(status, 0) << output;
    if (!said.empty()) {
        EXPECT_NE(output.find("hdhair-record: warning: "), std::string::npos) << output;
    }
    EXPECT_NE(output.find(said), std::string::npos) << "expected '" << said << "' in:\n" << output;
    EXPECT_EQ(output.find("hdhair-record: error"), std::string::npos) << output;
    ASSERT_TRUE(fs::exists(folder / input.output)) << output;
    const Image image = readImage((folder / input.output).string());
    for (float value : image.pixels) ASSERT_TRUE(std::isfinite(value));
}

std::vector<std::string> readers() {
#if HDHAIR_WITH_USD
    return {"embedded", "usd"};
#else
    return {"embedded"};
#endif
}

std::vector<Verdict> verdicts() {
    std::vector<Verdict> all;
    for (const VerdictCase& input : catalogue())
        for (const std::string& reader : readers()) all.push_back({input, reader});
    return all;
}

INSTANTIATE_TEST_SUITE_P(Catalogue, ReaderVerdicts, ::testing::ValuesIn(verdicts()),
                         [](const ::testing::TestParamInfo<Verdict>& tested) {
                             return tested.param.input.name + "_" + tested.param.reader;
                         });

// AddressSanitizer reserves terabytes of address space, so ulimit -v cannot
// bound a sanitized build; this test is left out of it.
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define HDHAIR_UNDER_ADDRESS_SANITIZER 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define HDHAIR_UNDER_ADDRESS_SANITIZER 1
#endif

#ifndef HDHAIR_UNDER_ADDRESS_SANITIZER
// --imageWidth 16384 where the process may take 3 GB (ulimit -v): a one-line
// error with what the frame needs and what fits, before anything is
// allocated (not std::bad_alloc part way), in both readers.
TEST(HugeImages, AreRefusedBeforeAnythingIsAllocated) {
    const fs::path folder = fs::temp_directory_path() / "hdhair-reader-verdicts" / "hugeImage";
    fs::remove_all(folder);
    fs::create_directories(folder);
    std::ofstream(folder / "stage.usda") << curvesStage("");
    for (const std::string& reader : readers()) {
        SCOPED_TRACE(reader);
        std::string output;
        const int status =
            runCommand("(ulimit -v 3000000; " + std::string(HDHAIR_RECORD) + " --reader " + reader +
                           " --camera /cam -w 16384 " + shellQuoted((folder / "stage.usda").string()) + " " +
                           shellQuoted((folder / "out.exr").string()) + ")",
                       &output);
        EXPECT_EQ(status, 1) << output;
        EXPECT_EQ(lineCount(output), 1) << output;
        EXPECT_NE(output.find("hdhair-record: error: a 16384x16384 frame needs about"), std::string::npos) << output;
        EXPECT_NE(output.find("this process can take (ulimit -v); at this shape at most"), std::string::npos)
            << output;
        EXPECT_FALSE(fs::exists(folder / "out.exr"));
    }
}
#endif

}  // namespace
}  // namespace hdhair::testenv
