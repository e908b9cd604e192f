#include "hdHair/bench/AccuracyBench.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/image/DisplayTransform.h"
#include "hdHair/image/ImageComparison.h"
#include "hdHair/image/ImageWriter.h"
#include "hdHair/reference/CyclesFrame.h"
#include "hdHair/plan/QualityPresets.h"
#include "hdHair/render/Renderer.h"
#include "hdHair/scene/Scene.h"
#include "hdHair/bench/AccuracyMatrix.h"
#include "hdHair/bench/BenchLights.h"

namespace hdhair::accuracy {

namespace {

using Clock = std::chrono::steady_clock;

// Median and spread ((largest - smallest) / median) of some times.
nlohmann::json summarize(std::vector<double> milliseconds) {
    std::sort(milliseconds.begin(), milliseconds.end());
    const size_t n = milliseconds.size();
    const double median = n % 2 ? milliseconds[n / 2] : 0.5 * (milliseconds[n / 2 - 1] + milliseconds[n / 2]);
    return {{"medianMs", median},
            {"spread", median > 0.0 ? (milliseconds.back() - milliseconds.front()) / median : 0.0},
            {"samplesMs", milliseconds}};
}

std::string firstLineOf(const std::string& path) {
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);
    return line;
}

std::string cpuModel() {
    std::ifstream in("/proc/cpuinfo");
    for (std::string line; std::getline(in, line);)
        if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
    return "unknown";
}

std::string joined(const std::vector<std::string>& settings) {
    std::string text;
    for (const std::string& setting : settings) text += (text.empty() ? "" : " ") + setting;
    return text;
}

// Every frame of a Cycles comparison, hdHair's and Cycles', is shaded so:
// Kajiya-Kay has no physical counterpart.
const std::vector<std::string> kCyclesShading = {"shadingModel=marschner"};

nlohmann::json errorJson(const RelativeColorError& error) {
    return {{"blockRmse", error.rootMeanSquare}, {"sumRatio", error.sumRatio}, {"largest", error.largest}};
}

// A stage path-traced by Cycles: full path tracing with two seeds (their
// difference is the noise floor) and single scattering.
struct CyclesFrames {
    Image full, otherSeed, single;
    nlohmann::json description;
};

CyclesFrames renderCyclesFrames(const AccuracyStage& stage, const CyclesComparison& comparison) {
    const RenderSettings settings = RenderSettings::fromAssignments(Complexity::Low, kCyclesShading);
    CyclesFraming framing;
    framing.camera = stage.camera;
    CyclesFrames frames;
    nlohmann::json seconds = nlohmann::json::object();
    std::string version;
    auto render = [&](const char* name, int seed, int maxBounces) {
        CyclesFrameRequest request;
        request.blender = comparison.blender;
        request.options.samples = comparison.samples;
        request.options.seed = seed;
        request.options.maxBounces = maxBounces;
        Clock::time_point last = Clock::now();
        request.progress = [&](const CyclesProgress& progress) {
            if (std::chrono::duration<double>(Clock::now() - last).count() < 10.0) return;
            last = Clock::now();
            std::fprintf(stderr, "hdhair-bench: %s, Cycles %s: sample %d/%d\n", stage.name.c_str(), name,
                         progress.sample, progress.samples);
        };
        Diagnostics diagnostics;
        const Clock::time_point start = Clock::now();
        CyclesFrame frame = renderCyclesFrame(*stage.scene, framing, settings, request, diagnostics);
        const double wall = std::chrono::duration<double>(Clock::now() - start).count();
        seconds[name] = {{"wall", wall}, {"render", frame.result.renderSeconds}};
        version = frame.result.blenderVersion;
        std::fprintf(stderr, "hdhair-bench: %s, Cycles %s: %d samples in %.1f s (%.1f s with export and start-up)\n",
                     stage.name.c_str(), name, frame.result.samplesDone, frame.result.renderSeconds, wall);
        if (!comparison.imagesFolder.empty())
            writeImage(frame.color, fmt::format("{}/{}.cycles-{}.exr", comparison.imagesFolder, stage.name, name),
                       ImageColor{settings.renderingSpace(), nullptr, nullptr, true},
                       cyclesFrameMetadata(request.options, frame.result));
        return std::move(frame.color);
    };
    frames.full = render("full", 0, CyclesRenderOptions().maxBounces);
    frames.otherSeed = render("full-seed1", 1, CyclesRenderOptions().maxBounces);
    frames.single = render("single", 0, 0);
    frames.description = {
        {"version", version},
        {"samples", comparison.samples},
        {"block", comparison.block},
        {"seconds", seconds},
        // The error a frame as exact as Cycles itself would still show.
        {"noiseFloor", errorJson(blockRelativeColorError(frames.otherSeed, frames.full, comparison.block))},
        {"pixelNoiseFloor", relativeColorError(frames.otherSeed, frames.full).rootMeanSquare},
        // What leaving out every scattering event after the first costs.
        {"singleAgainstFull", errorJson(blockRelativeColorError(frames.single, frames.full, comparison.block))}};
    return frames;
}

class StageBench {
public:
    // `common` goes under every frame's settings (the Cycles comparison's
    // shading); `cycles`, when given, is what every row is also compared with.
    StageBench(Renderer& renderer, AccuracyStage& stage, const DisplayTransform& display, int repetitions,
               std::vector<std::string> common, const CyclesFrames* cycles, int block)
        : renderer_(renderer), stage_(stage), display_(display), repetitions_(repetitions), common_(std::move(common)),
          cycles_(cycles), block_(block) {}

    // quality=reference over `base`, rendered once per base.
    const Image& reference(const std::vector<std::string>& base) {
        const std::string key = joined(base);
        auto found = references_.find(key);
        if (found != references_.end()) return found->second;
        std::vector<std::string> settings = base;
        settings.push_back("quality=reference");
        Clock::time_point start = Clock::now();
        RenderResult result = render(settings);
        referenceSeconds_[key] = std::chrono::duration<double>(Clock::now() - start).count();
        return references_.emplace(key, std::move(result.color)).first->second;
    }

    // One row: an untimed frame (its image is compared), then the timed
    // ones; with `ownError`, the same settings once more at the reference's
    // samples per pixel (below). A row of settings measured before is that
    // row again: every ladder passes through the defaults.
    nlohmann::json measure(const std::vector<std::string>& base, const Step& step, bool ownError) {
        std::vector<std::string> settings = base;
        settings.insert(settings.end(), step.settings.begin(), step.settings.end());
        const std::string key = joined(settings);
        if (auto found = rows_.find(key); found != rows_.end()) {
            nlohmann::json row = found->second;
            row["label"] = step.label;
            row["isDefault"] = step.isDefault;
            return row;
        }
        const Image& truth = reference(base);
        RenderResult first = render(settings);
        std::vector<double> frames;
        std::map<std::string, std::vector<double>> passes;
        for (int i = 0; i < repetitions_; ++i) {
            RenderResult timed = render(settings);
            frames.push_back(timed.stats.totalMilliseconds);
            for (const PassTiming& pass : timed.stats.passes) passes[pass.name].push_back(pass.milliseconds);
        }
        nlohmann::json passJson = nlohmann::json::object();
        for (auto& [name, times] : passes) passJson[name] = summarize(times);
        const ImageComparison linear = compareImages(first.color, truth, exactWithin(1.0 / 255.0));
        CoveredPixelTolerance displayTolerance;
        displayTolerance.threshold = kDisplayThreshold;
        displayTolerance.allowedShareOverThreshold = 1.0;
        displayTolerance.outlierLimit = 2.0;  // code values are within [0, 1]: no outliers
        const ImageComparison shown = compareImages(displayImage(first.color, display_, false),
                                                    displayImage(truth, display_, false), displayTolerance);
        // The approximation's own error: at one sample a pixel, sub-pixel
        // strands alias, and that floor (the supersampling row's error) hides
        // what a setting changes; rendered with the reference's samples the
        // step differs from the reference only in its approximation and the
        // other settings' defaults. The trend checks read this one.
        ImageComparison own = linear;
        if (ownError) {
            std::vector<std::string> sampled = settings;
            sampled.push_back("supersampling=" + *presetValue(Quality::Reference, "supersampling"));
            own = compareImages(render(sampled).color, truth, exactWithin(1.0 / 255.0));
        }
        nlohmann::json row = {{"stage", stage_.name},
                {"label", step.label},
                {"settings", settings},
                {"isDefault", step.isDefault},
                {"frame", summarize(frames)},
                {"passes", passJson},
                {"error",
                 {{"rmse", linear.rootMeanSquare},
                  {"max", linear.maxDifference},
                  {"displayShare", shown.shareOverThreshold},
                  {"coveredPixels", linear.coveredPixels},
                  {"ownRmse", own.rootMeanSquare},
                  {"ownMax", own.maxDifference}}},
                {"path", first.stats.transparency},
                {"fallback", first.stats.fallback},
                {"segments", first.stats.segments}};
        if (cycles_)
            row["cycles"] = {{"full", errorJson(blockRelativeColorError(first.color, cycles_->full, block_))},
                             {"single", errorJson(blockRelativeColorError(first.color, cycles_->single, block_))}};
        rows_[key] = row;
        return row;
    }

    nlohmann::json describe() const {
        nlohmann::json references = nlohmann::json::object();
        for (const auto& [key, seconds] : referenceSeconds_) references[key.empty() ? "(none)" : key] = seconds;
        nlohmann::json stage = {{"name", stage_.name},
                                {"path", stage_.path},
                                {"width", stage_.camera.imageWidth},
                                {"height", stage_.camera.imageHeight},
                                {"referenceSeconds", references}};
        if (cycles_) stage["cycles"] = cycles_->description;
        return stage;
    }

private:
    // A frame that rebuilds its shadow maps (the lights turned back and forth).
    RenderResult render(const std::vector<std::string>& rowSettings) {
        std::vector<std::string> settings = common_;
        settings.insert(settings.end(), rowSettings.begin(), rowSettings.end());
        settings.push_back("passTimings=true");
        turnLightsAboutY(*stage_.scene, (forth_ = !forth_) ? 1e-6 : -1e-6);
        Diagnostics diagnostics;
        return renderer_.render(*stage_.scene, stage_.camera, RenderSettings::fromAssignments(Complexity::Low, settings),
                                diagnostics);
    }

    Renderer& renderer_;
    AccuracyStage& stage_;
    const DisplayTransform& display_;
    int repetitions_;
    std::vector<std::string> common_;
    const CyclesFrames* cycles_;
    int block_;
    bool forth_ = false;
    std::map<std::string, Image> references_;
    std::map<std::string, double> referenceSeconds_;
    std::map<std::string, nlohmann::json> rows_;  // by their settings
};

// The progress line's comparison with Cycles, when the row has one.
std::string cyclesSummary(const nlohmann::json& row) {
    if (!row.contains("cycles")) return "";
    return fmt::format(", against Cycles {:.3f} (sum {:.2f}), single scattering {:.3f}",
                       row["cycles"]["full"]["blockRmse"].get<double>(), row["cycles"]["full"]["sumRatio"].get<double>(),
                       row["cycles"]["single"]["blockRmse"].get<double>());
}

}  // namespace

nlohmann::json runAccuracyBench(Renderer& renderer, std::vector<AccuracyStage>& stages, const AccuracyRun& run) {
    const Clock::time_point start = Clock::now();
    DisplayTransformOptions view;
    view.mode = ColorCorrectionMode::OpenColorIO;  // the shipped config's default display and view
    const DisplayTransform display = DisplayTransform::create(view);
    auto chosen = [&](const std::string& name) {
        return run.approximations.empty() ||
               std::find(run.approximations.begin(), run.approximations.end(), name) != run.approximations.end();
    };
    std::vector<Approximation> matrix;
    for (Approximation& approximation : accuracyMatrix(run.quick))
        if (chosen(approximation.name)) matrix.push_back(std::move(approximation));
    nlohmann::json report;
    report["command"] = run.command;
    report["quick"] = run.quick;
    report["repetitions"] = run.repetitions;
    report["machine"] = {{"cpu", cpuModel()},
                         {"cores", std::thread::hardware_concurrency()},
                         {"gl", renderer.glDescription()},
                         {"glDevice", renderer.glDevice()},
                         {"loadAverageAtStart", firstLineOf("/proc/loadavg")}};
    report["display"] = {{"transform", display.summary()}, {"threshold", kDisplayThreshold}};
    const std::vector<std::string> common = run.cycles ? kCyclesShading : std::vector<std::string>();
    report["commonSettings"] = common;
    report["approximations"] = nlohmann::json::array();
    for (const Approximation& approximation : matrix) {
        nlohmann::json steps = nlohmann::json::array();
        for (const Step& step : approximation.steps) steps.push_back(step.label);
        report["approximations"].push_back({{"name", approximation.name},
                                            {"trades", approximation.trades},
                                            {"base", approximation.base},
                                            {"trend", toString(approximation.trend)},
                                            {"checkedBeyondDefault", approximation.checkedBeyondDefault},
                                            {"steps", steps}});
    }
    report["stages"] = nlohmann::json::array();
    report["rows"] = nlohmann::json::array();
    for (AccuracyStage& stage : stages) {
        std::optional<CyclesFrames> cycles;
        if (run.cycles) cycles = renderCyclesFrames(stage, *run.cycles);
        StageBench bench(renderer, stage, display, run.repetitions, common, cycles ? &*cycles : nullptr,
                         run.cycles ? run.cycles->block : 1);
        for (const Approximation& approximation : matrix)
            for (const Step& step : approximation.steps) {
                nlohmann::json row = bench.measure(approximation.base, step, approximation.ownErrorAtReferenceSampling);
                row["approximation"] = approximation.name;
                std::fprintf(stderr, "hdhair-bench: %s, %s %s: %.1f ms, RMSE %.5f (own %.5f)%s\n", stage.name.c_str(),
                             approximation.name.c_str(), step.label.c_str(), row["frame"]["medianMs"].get<double>(),
                             row["error"]["rmse"].get<double>(), row["error"]["ownRmse"].get<double>(),
                             cyclesSummary(row).c_str());
                report["rows"].push_back(row);
            }
        for (const Step& step : chosen("preset") ? presetSteps() : std::vector<Step>()) {
            nlohmann::json row = bench.measure({}, step, false);
            row["approximation"] = "preset";
            std::fprintf(stderr, "hdhair-bench: %s, %s: %.1f ms, RMSE %.5f%s\n", stage.name.c_str(), step.label.c_str(),
                         row["frame"]["medianMs"].get<double>(), row["error"]["rmse"].get<double>(),
                         cyclesSummary(row).c_str());
            report["rows"].push_back(row);
        }
        report["stages"].push_back(bench.describe());
    }
    report["machine"]["loadAverageAtEnd"] = firstLineOf("/proc/loadavg");
    report["seconds"] = std::chrono::duration<double>(Clock::now() - start).count();
    return report;
}

}  // namespace hdhair::accuracy
