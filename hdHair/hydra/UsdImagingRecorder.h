#pragma once
// hdhair-record's OpenUSD front end: opens the stage with OpenUSD and renders
// it through UsdImagingGL and the hdHair plugin, the path usdrecord takes with
// --renderer HdHair --disableGpu. This header has no pxr in it, so
// hdhair-record builds the same with or without OpenUSD; the implementation
// exists only when the plugin is built (HDHAIR_WITH_USD).

#include <functional>
#include <string>
#include <vector>

#include "hdHair/image/Image.h"
#include "hdHair/plan/RenderSettings.h"

namespace hdhair::hydra {

struct UsdImagingRecordRequest {
    std::string stagePath;
    std::string camera;          // prim path; empty: hdHair's framing camera
    int imageWidth = 960;
    double time = 0.0;           // NaN: UsdTimeCode::Default(); -infinity: EarliestTime()
    Complexity complexity = Complexity::Low;
    std::vector<std::string> settings;  // NAME=VALUE, as for --setting
    bool renderPurpose = false, proxyPurpose = true, guidePurpose = false;
    FramingStyle framing = FramingStyle::FitAll;
    std::string pluginPath;      // folder holding the plugin's plugInfo.json
    // Each warning, one line ("<where>: <what>"), as it comes: the stage
    // checks', OpenUSD's and the plugin's, none held back past the stage's
    // checks (a refused stage gives its one error line alone).
    std::function<void(const std::string& warning)> warn;
};

struct UsdImagingRecordResult {
    Image color;                 // RGBA, linear, pre-multiplied (the color AOV)
    std::string camera;          // what was used
    // The plugin's report of the frame: RenderStats as JSON (passes and
    // timings, hdHair/render/RenderStats.h) and the plan as --explain prints it.
    std::string frameStatsJson;
    std::string plan;
};

// Throws InputError for a stage that cannot be used (the same verdicts as
// the embedded reader: docs/hard-cases.md), std::runtime_error for a frame
// that could not be rendered; each with a one-line reason.
UsdImagingRecordResult recordWithUsdImaging(const UsdImagingRecordRequest& request);

}  // namespace hdhair::hydra
