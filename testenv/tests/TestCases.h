#pragma once
// testenv's stage snapshots: each case is a folder testenv/cases/<name>/ with
//   case.json     what to render and how close it must stay:
//                 {"description": "...",
//                  "stage": "stage.usda" or a path from the case folder to a
//                           shared stage ("../../stages/bases.usda"),
//                  "arguments": ["--complexity", "medium", "-s", "shadowMode=off", ...]
//                              (hdhair-record's, without the display options),
//                  "frames": "1:3"   (optional: hdhair-record --frames; one
//                                     baseline per frame, baseline.0001.exr ...),
//                  "display": {"view": "sRGB", "look": "", "display": ""}
//                              (an OCIO display of the shipped config),
//                  "thresholds": {"fail": 0.008, "failpercent": 0.25,
//                                 "hardfail": 0.25, "hardfailAllowed": 0},
//                  "mutations": ["unsorted", "shadowsOff", ...]}
//                              (each must make the case fail: caseMutation)
//   baseline.exr  the linear render (its colour space in its metadata)
//   baseline.png  its display image, for people to look at and review.
// A case renders with hdhair-record to EXR; the actual and the baseline EXR
// both go through the same OCIO display transform (DisplayTransform, from
// the colour space each EXR names) and are compared over covered pixels
// (ImageComparison) with the thresholds as idiff would read them: a pixel
// over `fail` counts, the case fails when more than `failpercent` % of
// covered pixels count or when more than `hardfailAllowed` pixels (idiff: 0)
// differ by over `hardfail`.

#include <string>
#include <vector>

#include "hdHair/image/DisplayTransform.h"
#include "hdHair/image/Image.h"
#include "hdHair/image/ImageComparison.h"

namespace hdhair::testenv {

struct TestCase {
    std::string name;    // the folder's name
    std::string folder;  // absolute
    std::string description;
    std::string stage;   // absolute
    std::vector<std::string> arguments;
    std::string frames;  // "" : one frame
    DisplayTransformOptions display;  // openColorIO; its colour space comes from each EXR
    CoveredPixelTolerance tolerance;
    std::vector<std::string> mutations;  // caseMutation's names
    // True when every argument is one usdrecord also takes (so the case may
    // run through usdrecord --renderer HdHair too).
    bool usdrecordCompatible() const;
};

// A change to a case that must make it fail against its baseline: a test
// that passes with sorting off, the shadows swapped, the other shading
// model or another display view would not catch that defect. Settings go
// after the case's own arguments (the last one wins); a view replaces the
// case's display view.
// Stage edits are made to the scene the embedded reader reads, rendered in
// the test's process with the case's arguments.
enum class StageEdit { None, DropStrand, WidenStrands };
struct CaseMutation {
    std::vector<std::string> arguments;
    std::string view;
    StageEdit edit = StageEdit::None;
};
// "unsorted", "binSorted" (transparency), "shadowsOff", "shadowsOn"
// (deepOpacity), "kajiyaKay", "marschner" (shadingModel), "rawDisplay",
// "srgbDisplay" (the view), "dropStrand" (the middle curve of the prim with
// the most curves left undrawn), "widths1.5" (every authored width 1.5 times
// as wide). Throws std::runtime_error for another name.
CaseMutation caseMutation(const std::string& name);

// The case folders under testenv/cases, sorted by name.
std::vector<std::string> testCaseFolders();
// A case folder's name as a GoogleTest parameter name (letters, digits, _).
std::string caseTestName(const std::string& folder);
// Reads `folder`/case.json; throws std::runtime_error naming the file and the
// key for anything missing or of the wrong type.
TestCase loadTestCase(const std::string& folder);

// hdhair-record's output name for `stem` in `folder`: stem.exr, or
// stem.####.exr when the case renders frames.
std::string framePattern(const TestCase& testCase, const std::string& folder, const std::string& stem);
// The EXR files of `stem` in `folder`: stem.exr, or one per frame
// (stem.0001.exr, ...).
std::vector<std::string> frameFiles(const TestCase& testCase, const std::string& folder, const std::string& stem);

// Renders the case with hdhair-record into `outputFolder` (actual.exr, or
// actual.####.exr); returns hdhair-record's exit status, its output in `log`.
int renderCase(const TestCase& testCase, const std::string& outputFolder, std::string* log);

// The colour space an hdHair EXR names in its metadata (lin_rec709, ACEScg).
std::string colorSpaceOf(const std::string& exrPath);

// The display image of a linear EXR as the case shows it.
Image caseDisplayImage(const TestCase& testCase, const std::string& exrPath);

struct CaseVerdict {
    bool passed = false;
    std::string report;  // one paragraph: what was compared, the statistics, the files written
};

// Compares one rendered frame with its baseline, both shown through the
// case's display transform. On failure writes, into `outputFolder`,
// <stem>.actual.png (the actual display image), <stem>.expected.png and
// <stem>.difference.png (differenceImage), and names them in the report.
CaseVerdict compareWithBaseline(const TestCase& testCase, const std::string& actualExr,
                                const std::string& baselineExr, const std::string& outputFolder);

// Makes `actualExr` the baseline (copied to `baselineExr`) and writes its
// display image beside it as the .png of the same name.
void updateBaseline(const TestCase& testCase, const std::string& actualExr, const std::string& baselineExr);

}  // namespace hdhair::testenv
