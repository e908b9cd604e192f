#include "TestCases.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "Commands.h"
#include "StageRendering.h"
#include "hdHair/image/ImageWriter.h"
#include "hdHair/base/FrameSpec.h"

namespace hdhair::testenv {
namespace fs = std::filesystem;
namespace {

const nlohmann::json& required(const nlohmann::json& object, const char* key, const std::string& file) {
    if (!object.is_object() || !object.contains(key))
        throw std::runtime_error(file + ": missing \"" + key + "\"");
    return object.at(key);
}

std::string stringAt(const nlohmann::json& object, const char* key, const std::string& file,
                     const std::string& fallback = std::string(), bool optional = true) {
    if (!object.contains(key)) {
        if (optional) return fallback;
        required(object, key, file);
    }
    if (!object.at(key).is_string()) throw std::runtime_error(file + ": \"" + key + "\" must be a string");
    return object.at(key).get<std::string>();
}

double numberAt(const nlohmann::json& object, const char* key, const std::string& file) {
    const nlohmann::json& value = required(object, key, file);
    if (!value.is_number() || value.get<double>() < 0.0)
        throw std::runtime_error(file + ": \"" + key + "\" must be a number >= 0");
    return value.get<double>();
}

}  // namespace

std::string colorSpaceOf(const std::string& exrPath) {
    auto input = OIIO::ImageInput::open(exrPath);
    if (!input) throw std::runtime_error("cannot read " + exrPath);
    std::string space = input->spec().get_string_attribute("colorSpace");
    if (space.empty()) throw std::runtime_error(exrPath + " does not name its colour space");
    return space;
}

bool TestCase::usdrecordCompatible() const {
    // usdrecord's options with a value, and without; hdHair's settings (-s)
    // and framing of its own are not among them.
    for (size_t i = 0; i < arguments.size(); ++i) {
        const std::string& argument = arguments[i];
        if (argument == "--camera" || argument == "--complexity" || argument == "-c" || argument == "--imageWidth" ||
            argument == "-w" || argument == "--purposes") {
            ++i;
            continue;
        }
        return false;
    }
    return std::find(arguments.begin(), arguments.end(), "--camera") != arguments.end();
}

CaseMutation caseMutation(const std::string& name) {
    static const std::map<std::string, CaseMutation> mutations = {
        {"unsorted", {{"-s", "transparency=unsorted"}, ""}},
        {"binSorted", {{"-s", "transparency=binSorted"}, ""}},
        {"shadowsOff", {{"-s", "shadowMode=off"}, ""}},
        {"shadowsOn", {{"-s", "shadowMode=deepOpacity"}, ""}},
        {"kajiyaKay", {{"-s", "shadingModel=kajiyaKay"}, ""}},
        {"marschner", {{"-s", "shadingModel=marschner"}, ""}},
        {"rawDisplay", {{}, "Raw"}},
        {"srgbDisplay", {{}, "sRGB"}},
        {"dropStrand", {{}, "", StageEdit::DropStrand}},
        {"widths1.5", {{}, "", StageEdit::WidenStrands}},
    };
    auto found = mutations.find(name);
    if (found == mutations.end())
        throw std::runtime_error("unknown case mutation '" + name +
                                 "' (unsorted, binSorted, shadowsOff, shadowsOn, kajiyaKay, marschner, rawDisplay, "
                                 "srgbDisplay, dropStrand, widths1.5)");
    return found->second;
}

std::vector<std::string> testCaseFolders() {
    std::vector<std::string> folders;
    for (const fs::directory_entry& entry : fs::directory_iterator(sourcePath("testenv/cases")))
        if (entry.is_directory() && fs::exists(entry.path() / "case.json")) folders.push_back(entry.path().string());
    std::sort(folders.begin(), folders.end());
    return folders;
}

std::string caseTestName(const std::string& folder) {
    std::string name = fs::path(folder).filename().string();
    for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return name;
}

TestCase loadTestCase(const std::string& folder) {
    const std::string file = (fs::path(folder) / "case.json").string();
    std::ifstream in(file);
    if (!in) throw std::runtime_error("cannot read " + file);
    const nlohmann::json json = nlohmann::json::parse(in, nullptr, false);
    if (json.is_discarded() || !json.is_object()) throw std::runtime_error(file + ": not a JSON object");

    TestCase testCase;
    testCase.folder = folder;
    testCase.name = fs::path(folder).filename().string();
    testCase.description = stringAt(json, "description", file, "", false);
    testCase.stage = fs::weakly_canonical(fs::path(folder) / stringAt(json, "stage", file, "", false)).string();
    if (!fs::exists(testCase.stage)) throw std::runtime_error(file + ": stage " + testCase.stage + " does not exist");
    const nlohmann::json& arguments = required(json, "arguments", file);
    if (!arguments.is_array()) throw std::runtime_error(file + ": \"arguments\" must be an array of strings");
    for (const nlohmann::json& argument : arguments) {
        if (!argument.is_string()) throw std::runtime_error(file + ": \"arguments\" must be an array of strings");
        testCase.arguments.push_back(argument.get<std::string>());
    }
    testCase.frames = stringAt(json, "frames", file);

    const nlohmann::json& display = required(json, "display", file);
    testCase.display.mode = ColorCorrectionMode::OpenColorIO;
    testCase.display.config = DisplayTransform::shippedConfigPath();
    testCase.display.display = stringAt(display, "display", file);
    testCase.display.view = stringAt(display, "view", file);
    testCase.display.look = stringAt(display, "look", file);

    const nlohmann::json& thresholds = required(json, "thresholds", file);
    testCase.tolerance.threshold = numberAt(thresholds, "fail", file);
    testCase.tolerance.allowedShareOverThreshold = numberAt(thresholds, "failpercent", file) / 100.0;
    testCase.tolerance.outlierLimit = numberAt(thresholds, "hardfail", file);
    testCase.tolerance.allowedOutliers =
        thresholds.contains("hardfailAllowed") ? size_t(numberAt(thresholds, "hardfailAllowed", file)) : 0;
    if (testCase.tolerance.outlierLimit < testCase.tolerance.threshold)
        throw std::runtime_error(file + ": \"hardfail\" must not be below \"fail\"");
    if (json.contains("mutations")) {
        const nlohmann::json& mutations = json.at("mutations");
        if (!mutations.is_array()) throw std::runtime_error(file + ": \"mutations\" must be an array of names");
        for (const nlohmann::json& mutation : mutations) {
            if (!mutation.is_string()) throw std::runtime_error(file + ": \"mutations\" must be an array of names");
            caseMutation(mutation.get<std::string>());  // an unknown name is an error here
            testCase.mutations.push_back(mutation.get<std::string>());
        }
    }
    return testCase;
}

std::string framePattern(const TestCase& testCase, const std::string& folder, const std::string& stem) {
    return (fs::path(folder) / (testCase.frames.empty() ? stem + ".exr" : stem + ".####.exr")).string();
}

std::vector<std::string> frameFiles(const TestCase& testCase, const std::string& folder, const std::string& stem) {
    const std::string pattern = framePattern(testCase, folder, stem);
    if (testCase.frames.empty()) return {pattern};
    std::vector<std::string> files;
    for (double frame : parseFrameSpec(testCase.frames)) files.push_back(expandFramePlaceholder(pattern, frame));
    return files;
}

int renderCase(const TestCase& testCase, const std::string& outputFolder, std::string* log) {
    std::string command = std::string("'") + HDHAIR_RECORD + "'";
    for (const std::string& argument : testCase.arguments) command += " " + shellQuoted(argument);
    if (!testCase.frames.empty()) command += " --frames " + shellQuoted(testCase.frames);
    command += " " + shellQuoted(testCase.stage) + " " + shellQuoted(framePattern(testCase, outputFolder, "actual"));
    return runCommand(command, log);
}

Image caseDisplayImage(const TestCase& testCase, const std::string& exrPath) {
    DisplayTransformOptions options = testCase.display;
    options.colorSpace = colorSpaceOf(exrPath);
    return displayImage(readImage(exrPath), DisplayTransform::create(options), false);
}

CaseVerdict compareWithBaseline(const TestCase& testCase, const std::string& actualExr,
                                const std::string& baselineExr, const std::string& outputFolder) {
    CaseVerdict verdict;
    const std::string view = testCase.display.view.empty() ? std::string("the default view") : testCase.display.view;
    if (!fs::exists(baselineExr)) {
        verdict.report = fmt::format("{}: no baseline {} (HDHAIR_UPDATE_BASELINES=1 writes it)", testCase.name,
                                     baselineExr);
        return verdict;
    }
    const Image actual = caseDisplayImage(testCase, actualExr);
    const Image expected = caseDisplayImage(testCase, baselineExr);
    const ImageComparison comparison = compareImages(actual, expected, testCase.tolerance);
    verdict.passed = comparison.passed;
    verdict.report = fmt::format("{} ({}), {} through OCIO {}{}: {}", testCase.name, fs::path(baselineExr).filename().string(),
                                 colorSpaceOf(actualExr), view,
                                 testCase.display.look.empty() ? "" : " + look " + testCase.display.look,
                                 comparison.description);
    if (comparison.passed) return verdict;
    std::string stem = fs::path(actualExr).stem().string();  // actual, or actual.0001
    stem.replace(0, std::string("actual").size(), testCase.name);
    const std::string base = (fs::path(outputFolder) / stem).string();
    writeImage(actual, base + ".actual.png", {RenderingSpace::LinearRec709, nullptr, &actual});
    writeImage(expected, base + ".expected.png", {RenderingSpace::LinearRec709, nullptr, &expected});
    if (comparison.sizesMatch) {
        const Image difference = differenceImage(actual, expected, testCase.tolerance);
        writeImage(difference, base + ".difference.png", {RenderingSpace::LinearRec709, nullptr, &difference});
    }
    verdict.report += fmt::format("\n  wrote {0}.actual.png, {0}.expected.png{1} (differences x10, red over "
                                  "hardfail); the actual linear render is {2}",
                                  base, comparison.sizesMatch ? ", " + base + ".difference.png" : std::string(),
                                  actualExr);
    return verdict;
}

void updateBaseline(const TestCase& testCase, const std::string& actualExr, const std::string& baselineExr) {
    fs::copy_file(actualExr, baselineExr, fs::copy_options::overwrite_existing);
    const Image shown = caseDisplayImage(testCase, baselineExr);
    const std::string png = (fs::path(baselineExr).replace_extension(".png")).string();
    writeImage(shown, png, {RenderingSpace::LinearRec709, nullptr, &shown});
}

}  // namespace hdhair::testenv
