#pragma once
// hdhair-bench --accuracy: every approximation of the matrix
// (AccuracyMatrix.h) and every quality preset rendered on each stage, timed
// over repetitions (median and spread, per pass and per frame), and compared
// with the stage's reference image (quality=reference over the
// approximation's base settings):
//  - RMSE and largest difference on pre-multiplied scene-linear RGBA over
//    covered pixels (ImageComparison.h, the image tests' rule);
//  - the share of covered pixels whose display code values (through the
//    shipped OCIO config's default view) differ by more than
//    kDisplayThreshold: what a viewer could see;
//  - "own" RMSE and largest difference: the step rendered once more with the
//    reference's samples per pixel, so the approximation's own error shows
//    above the aliasing of one sample a pixel (the trend checks read it).
// Every timed frame rebuilds its shadow maps (the lights are turned by a
// microradian first, BenchLights.h), so shadow settings cost what they cost
// after a light moved. The result is the report's JSON (AccuracyReport.h).
//
// With a Cycles comparison (docs/accuracy.md, "Against Cycles") each stage
// is also path-traced by Blender's Cycles from the scene hdHair renders
// (CyclesFrame.h), three times: full path tracing with two seeds and single
// scattering. Every frame, hdHair's and Cycles', is shaded with
// shadingModel=marschner (Kajiya-Kay has no physical counterpart), and every
// row gets its error against both Cycles frames over blocks of pixels
// (blockRelativeColorError): per pixel, a path-traced frame's error is its
// own noise. The stage records the noise floor (the two seeds against each
// other over the same blocks) and each Cycles frame's time.

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "hdHair/plan/CameraView.h"

namespace hdhair {

class Renderer;
class Scene;

namespace accuracy {

// Two 8-bit steps: beyond what rounding moves, the least a viewer could see.
constexpr double kDisplayThreshold = 2.0 / 255.0;

struct AccuracyStage {
    std::string name, path;
    Scene* scene = nullptr;
    CameraView camera;
};

struct CyclesComparison {
    int samples = 256;               // per pixel, each Cycles frame
    int block = 16;                  // pixels across a block of the errors
    std::string blender = "blender";
    std::string imagesFolder;        // where the Cycles frames are written as EXR (none when empty)
};

struct AccuracyRun {
    bool quick = false;
    int repetitions = 3;   // timed frames per configuration, after one untimed frame
    std::string command;   // as run, for the report
    std::optional<CyclesComparison> cycles;
    // Only these approximations (by name; "preset" for the presets); all
    // when empty.
    std::vector<std::string> approximations;
};

// Throws std::runtime_error when a reference cannot be rendered (exact
// transparency over its memory: the reference never falls back).
nlohmann::json runAccuracyBench(Renderer& renderer, std::vector<AccuracyStage>& stages, const AccuracyRun& run);

}  // namespace accuracy
}  // namespace hdhair
