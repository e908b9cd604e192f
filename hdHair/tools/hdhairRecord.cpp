// hdhair-record: renders a USD stage to images, with usdrecord's options
// where they apply. Reads the stage with the embedded .usda reader.
//
//   hdhair-record [options] usdFile outputImagePath
//
// Exit status: 0 on success; otherwise one line "hdhair-record: error: ..." and
//   1  the input or the arguments are wrong (unreadable stage, bad camera,
//      unwritable output): running again gives the same error;
//   2  the command line does not parse;
//   75 (EX_TEMPFAIL) the machine failed the frame (out of memory, no GL
//      context): another try, or another machine, may render it.
// hdhair-farm retries only 75 and frames killed by a signal.

#include <atomic>
#include <chrono>
#include <csignal>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <mutex>
#include <new>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "hdHair/base/AtomicFile.h"
#include "hdHair/base/Diagnostics.h"
#include "hdHair/base/InputError.h"
#include "hdHair/base/PrintableText.h"
#include "hdHair/gl/GlContext.h"
#include "hdHair/image/DisplayTransform.h"
#include "hdHair/image/ImageWriter.h"
#include "hdHair/reference/CyclesFrame.h"
#include "hdHair/plan/CameraView.h"
#include "hdHair/render/EmptyFrame.h"
#include "hdHair/render/Renderer.h"
#include "hdHair/plan/SettingOrigins.h"
#include "hdHair/scene/Scene.h"
#include "hdHair/scene/SceneValidation.h"
#include "hdHair/base/FrameSpec.h"
#include "hdHair/usda/SceneReader.h"
#include "hdHair/usda/Stage.h"
#if HDHAIR_WITH_USD
#include "hdHair/hydra/UsdImagingRecorder.h"
#endif

namespace {

using namespace hdhair;
using Clock = std::chrono::steady_clock;

constexpr size_t kWarningsPrinted = 20;
constexpr int kMachineFailed = 75;  // EX_TEMPFAIL: see the exit statuses above

#if HDHAIR_WITH_USD
constexpr const char* kDefaultReader = "usd";
#else
constexpr const char* kDefaultReader = "embedded";
#endif

struct Options {
    std::string usdFile, outputPath, camera, frames, complexity = "low", gl, statsFile, purposes = "proxy";
    std::string quality;  // --quality: the quality setting, before any --setting
    std::string reader = kDefaultReader;
    int imageWidth = 960;
    bool defaultTime = false, verbose = false, explain = false;
    bool check = false;  // --check: check the input as a render would, render nothing
    bool exrFloat32 = false;  // EXR as 32-bit floats, every value exact (else half, clamped to +-65504)
    std::vector<std::string> settings;
    // Colour management, as usdrecord's --colorCorrectionMode, with OCIO's choices.
    std::string colorCorrectionMode = "sRGB", ocioConfig, ocioDisplay, ocioView, ocioColorSpace, ocioLook;
    std::string displayTransformOn = "cpu";
    // --reference cycles: the frame path-traced by Blender's Cycles instead
    // (docs/cycles-reference.md), with these options.
    std::string reference;
    CyclesRenderOptions cycles;
    std::string blender = "blender";
    bool readerGiven = false;  // --reader on the command line
    bool framesGiven = false;  // --frames on the command line, even as ""
};

// The files this run wrote: a run that fails removes them, so that a failed
// frame range or an unwritable --stats leaves nothing behind (a batch job's
// outputs are all there, or its exit status says why none are).
std::vector<std::string> filesWritten;

void removeFilesWritten() {
    for (const std::string& path : filesWritten) {
        std::error_code ignored;
        std::filesystem::remove(path, ignored);
    }
    filesWritten.clear();
}


#if HDHAIR_WITH_USD
// The plugin's plugInfo.json folder: $HDHAIR_PLUGIN_RESOURCES when set, else
// where the build and install trees both put it beside this executable
// (bin/hdhair-record and plugin/usd/hdHair/resources).
std::string hydraPluginResources() {
    if (const char* path = std::getenv("HDHAIR_PLUGIN_RESOURCES")) return path;
    std::error_code error;
    std::filesystem::path executable = std::filesystem::read_symlink("/proc/self/exe", error);
    if (error) return std::string();
    return (executable.parent_path().parent_path() / "plugin" / "usd" / "hdHair" / "resources").string();
}
#endif

std::string describeTime(double time) {
    if (std::isnan(time)) return "default time";
    if (std::isinf(time)) return "earliest time";
    return fmt::format("time {}", time);
}

double millisecondsSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The display transform display formats go through (EXR stays scene-linear),
// starting from the frame's rendering space unless --ocioColorSpace says the
// image is in another. Throws std::invalid_argument with one line for an
// unknown mode, config or name (DisplayTransform::create lists the valid ones).
DisplayTransform displayTransformFor(const Options& options, RenderingSpace renderingSpace) {
    DisplayTransformOptions display;
    display.renderingSpace = toString(renderingSpace);
    if (!parseToken(options.colorCorrectionMode, &display.mode))
        throw std::invalid_argument("--colorCorrectionMode must be disabled, sRGB or openColorIO, not '" +
                                    options.colorCorrectionMode + "'");
    const bool anyOcio = !options.ocioConfig.empty() || !options.ocioDisplay.empty() || !options.ocioView.empty() ||
                         !options.ocioLook.empty();
    if (anyOcio && display.mode != ColorCorrectionMode::OpenColorIO)
        throw std::invalid_argument("--ocioConfig, --ocioDisplay, --ocioView and --ocioLook need "
                                    "--colorCorrectionMode openColorIO");
    if (options.displayTransformOn != "cpu" && options.displayTransformOn != "gpu")
        throw std::invalid_argument("--displayTransformOn must be cpu or gpu, not '" + options.displayTransformOn + "'");
    display.config = options.ocioConfig;
    display.display = options.ocioDisplay;
    display.view = options.ocioView;
    display.look = options.ocioLook;
    display.colorSpace = options.ocioColorSpace;
    return DisplayTransform::create(display);
}

// Writes a frame's image: EXR scene-linear, display formats through the
// display transform (made on the GPU already in `gpuDisplayed`, or here on
// the CPU, timed). Adds what it did to `frameStats`. Takes the linear image:
// a display image is made in its memory, so a frame's floats exist once.
void writeFrameImage(Image linear, const Image* gpuDisplayed, const DisplayTransform& display,
                     RenderingSpace space, const std::string& outputPath, bool exrFloat32, Diagnostics& diagnostics,
                     std::vector<PassTiming>& passes, nlohmann::json& frameStats, const ImageMetadata& metadata = {}) {
    ImageColor color;
    color.space = space;
    color.display = &display;
    color.exrFloat32 = exrFloat32;
    const bool sceneLinear = isSceneLinearImagePath(outputPath);
    Image shown;
    if (!sceneLinear) {
        if (gpuDisplayed) {
            color.displayed = gpuDisplayed;
        } else {
            Clock::time_point start = Clock::now();
            shown = displayImage(std::move(linear), display, !keepsAlpha(outputPath));
            passes.push_back({"displayTransform (cpu)", millisecondsSince(start)});
            color.displayed = &shown;
        }
    }
    Clock::time_point writeStart = Clock::now();
    // A display format reads only `color.displayed`; the linear image given
    // is checked for its size, so the display image stands in for it.
    const ImageWriteReport report =
        writeImage(color.displayed ? *color.displayed : linear, outputPath, color, metadata);
    filesWritten.push_back(outputPath);
    passes.push_back({"writeImage", millisecondsSince(writeStart)});
    if (report.pixelsClampedToHalf > 0)
        diagnostics.warn(outputPath, fmt::format("{} pixels exceed half float's largest value (65504) and were clamped "
                                                 "to it; --exrFloat32 writes them exactly",
                                                 report.pixelsClampedToHalf));
    nlohmann::json colorStats = display.describe();
    colorStats["output"] = sceneLinear ? "scene-linear" : "display";
    colorStats["renderingSpace"] = toString(space);
    if (!sceneLinear) colorStats["on"] = gpuDisplayed ? "gpu" : "cpu";
    frameStats["color"] = colorStats;
}

// Where the images and --stats go must be writable before anything is
// rendered: a farm job should fail in its first second, not after its frames.
void checkOutputTargets(const Options& options) {
    if (std::string why = whyNotWritable(options.outputPath); !why.empty())
        throw std::invalid_argument("cannot write '" + options.outputPath + "': " + why);
    if (!options.statsFile.empty())
        if (std::string why = whyNotWritable(options.statsFile); !why.empty())
            throw std::invalid_argument("cannot write --stats file '" + options.statsFile + "': " + why);
}

// The time codes to render, as usdrecord chooses them: --frames; the Default
// time code (NaN) with --defaultTime; else UsdTimeCode::EarliestTime()
// (-infinity), at which every attribute takes its first time sample.
std::vector<double> timesToRender(const Options& options) {
    if (options.framesGiven) return parseFrameSpec(options.frames);
    if (options.defaultTime) return {std::numeric_limits<double>::quiet_NaN()};
    return {-std::numeric_limits<double>::infinity()};
}

usda::SceneReadOptions purposesFrom(const std::string& purposes) {
    usda::SceneReadOptions read;
    read.renderPurpose = read.proxyPurpose = read.guidePurpose = false;
    std::string item;
    std::string list = purposes + ",";
    for (char c : list) {
        if (c != ',' && c != ' ') {
            item += c;
            continue;
        }
        if (item == "render") read.renderPurpose = true;
        else if (item == "proxy") read.proxyPurpose = true;
        else if (item == "guide") read.guidePurpose = true;
        else if (!item.empty() && item != "default")
            throw std::invalid_argument("unknown purpose '" + item + "' (use render, proxy, guide)");
        item.clear();
    }
    return read;
}

// The --setting assignments, after passTimings=true when the run reports
// what it did (--verbose, --explain, --stats) and --quality's preset: an
// explicit setting wins.
// Then interactiveBudgetMs=0 whatever was asked: a recorder writes full
// frames only, and through OpenUSD a preview would only delay them (run()
// warns when --setting asks for previews).
std::vector<std::string> settingAssignments(const Options& options) {
    std::vector<std::string> assignments;
    if (options.verbose || options.explain || !options.statsFile.empty()) assignments.push_back("passTimings=true");
    if (!options.quality.empty()) assignments.push_back("quality=" + options.quality);
    assignments.insert(assignments.end(), options.settings.begin(), options.settings.end());
    assignments.push_back("interactiveBudgetMs=0");
    return assignments;
}

// --explain: which of the --setting values, the complexity and the quality
// preset chose each setting.
void printSettingOrigins(const RenderSettings& settings) {
    std::printf("hdhair-record: settings (what chose each; the rest are defaults):\n%s",
                describeSettingOrigins(settings).c_str());
}

// The view of --camera's prim, checked (a bad lens is an error naming the
// prim and attribute); none without --camera.
std::optional<CameraView> cameraPrimView(const Options& options, const Scene& scene, Diagnostics& diagnostics) {
    if (options.camera.empty()) return std::nullopt;
    const CameraPrim* prim = scene.findCamera(options.camera);
    if (!prim) {
        std::string known;
        for (const auto& [path, entry] : scene.cameras()) known += (known.empty() ? "" : ", ") + path;
        throw InputError(options.usdFile + ": no camera at '" + options.camera + "'" +
                         (known.empty() ? " (the stage has no cameras)" : " (cameras: " + known + ")"));
    }
    return cameraViewFromPrim(checkedCamera(*prim, options.usdFile, diagnostics), options.imageWidth);
}

// The camera a stage rendered without --camera gets: its bounds framed as
// the framing setting says.
CameraView framingView(const Options& options, const RenderSettings& settings, const Scene& scene,
                       const SceneBounds& bounds) {
    return frameBounds(bounds.min, bounds.max, scene.info().upAxis, options.imageWidth, settings.values().framing);
}

std::string cameraDescription(const Options& options, const RenderSettings& settings) {
    return options.camera.empty() ? fmt::format("framing camera ({})", toString(settings.values().framing)) : options.camera;
}

#if HDHAIR_WITH_USD
// The plugin's warnings: the first kWarningsPrinted printed, every one kept
// for --stats.
struct PluginWarnings {
    size_t printed = 0;
    nlohmann::json warnings = nlohmann::json::array();  // every one, for --stats
    std::mutex mutex;  // the plugin's render thread warns too

    void warn(const std::string& warning) {
        const std::lock_guard<std::mutex> lock(mutex);
        if (printed++ < kWarningsPrinted)
            std::fprintf(stderr, "hdhair-record: warning: %s\n", printableText(warning).c_str());
        warnings.push_back({{"message", printableText(warning)}});
    }
};

// The request that records the frame at `time` through OpenUSD, framed as `framing` says.
hydra::UsdImagingRecordRequest usdImagingRequest(const Options& options, const usda::SceneReadOptions& purposes,
                                                 Complexity complexity, double time, FramingStyle framing,
                                                 PluginWarnings& warnings) {
    hydra::UsdImagingRecordRequest request;
    request.warn = [&warnings](const std::string& warning) { warnings.warn(warning); };
    request.stagePath = options.usdFile;
    request.camera = options.camera;
    request.imageWidth = options.imageWidth;
    request.time = time;
    request.complexity = complexity;
    request.settings = settingAssignments(options);
    request.renderPurpose = purposes.renderPurpose;
    request.proxyPurpose = purposes.proxyPurpose;
    request.guidePurpose = purposes.guidePurpose;
    request.framing = framing;
    request.pluginPath = hydraPluginResources();
    return request;
}

// The plugin's frame stats, parsed; an empty object when there are none or they do not parse.
nlohmann::json pluginFrameStats(const std::string& frameStatsJson) {
    nlohmann::json frameStats = nlohmann::json::object();
    if (!frameStatsJson.empty()) frameStats = nlohmann::json::parse(frameStatsJson, nullptr, false);
    if (frameStats.is_discarded()) frameStats = nlohmann::json::object();
    return frameStats;
}

// --verbose and --explain for one frame recorded through OpenUSD.
void printUsdImagingFrame(const Options& options, const RenderSettings& settings, double time,
                          const hydra::UsdImagingRecordResult& result, const nlohmann::json& frameStats, int width,
                          int height, double milliseconds, const std::string& outputPath) {
    if (options.explain) printSettingOrigins(settings);
    if (options.explain && !result.plan.empty())
        std::printf("hdhair-record: plan (%s):\n%s", describeTime(time).c_str(), result.plan.c_str());
    if (options.verbose && frameStats.contains("gl"))
        std::printf("hdhair-record: GL (the plugin's) %s on %s\n", frameStats.value("gl", "?").c_str(),
                    frameStats.value("glDevice", "?").c_str());
    if (options.verbose || options.explain) {
        std::string passes;
        for (const nlohmann::json& pass : frameStats.value("passes", nlohmann::json::array()))
            passes += fmt::format("{}{} {:.1f} ms", passes.empty() ? "" : ", ", pass.value("name", "?"),
                                  pass.value("milliseconds", 0.0));
        std::printf("hdhair-record: %s: %dx%d through OpenUSD and the HdHair plugin, camera %s, %.1f ms in all%s%s; "
                    "wrote %s\n",
                    describeTime(time).c_str(), width, height, result.camera.c_str(),
                    milliseconds, passes.empty() ? "" : "; plugin passes: ", passes.c_str(), outputPath.c_str());
    }
}

// One frame through OpenUSD and the plugin, recorded and written; returns its stats.
nlohmann::json recordFrameThroughUsdImaging(const Options& options, const usda::SceneReadOptions& purposes,
                                            const DisplayTransform& display, RenderingSpace space,
                                            Complexity complexity, double time, PluginWarnings& warnings) {
    const RenderSettings settings = RenderSettings::fromAssignments(complexity, settingAssignments(options));
    const hydra::UsdImagingRecordRequest request =
        usdImagingRequest(options, purposes, complexity, time, settings.values().framing, warnings);
    Clock::time_point start = Clock::now();
    hydra::UsdImagingRecordResult result = hydra::recordWithUsdImaging(request);
    double milliseconds = millisecondsSince(start);
    std::string outputPath =
        std::isfinite(time) ? expandFramePlaceholder(options.outputPath, time) : options.outputPath;
    // The plugin's own report of the frame (its passes and plan), as the
    // embedded path prints it; the total also covers opening the stage
    // and Hydra's sync.
    nlohmann::json frameStats = pluginFrameStats(result.frameStatsJson);
    // The plugin's colour AOV is scene-linear (hosts correct it once);
    // the display transform runs here, on the CPU.
    std::vector<PassTiming> writing;
    Diagnostics writeDiagnostics;
    writeDiagnostics.setListener([](const Diagnostic& warning) {
        std::fprintf(stderr, "hdhair-record: warning: %s: %s\n", warning.where.c_str(), warning.message.c_str());
    });
    const int width = result.color.width, height = result.color.height;
    writeFrameImage(std::move(result.color), nullptr, display, space, outputPath, options.exrFloat32,
                    writeDiagnostics, writing, frameStats);
    for (const PassTiming& pass : writing)
        frameStats["passes"].push_back({{"name", pass.name}, {"milliseconds", pass.milliseconds}});
    printUsdImagingFrame(options, settings, time, result, frameStats, width, height, milliseconds, outputPath);
    frameStats["reader"] = "usd";
    frameStats["camera"] = result.camera;
    frameStats["image"] = {{"width", width}, {"height", height}};
    frameStats["totalMilliseconds"] = milliseconds;
    frameStats["output"] = outputPath;
    return frameStats;
}
#endif

// The OpenUSD path: UsdStage, UsdImagingGL and the hdHair plugin, as
// usdrecord --renderer HdHair --disableGpu renders.
int runThroughUsdImaging(const Options& options, const usda::SceneReadOptions& purposes,
                         const DisplayTransform& display, RenderingSpace space) {
#if HDHAIR_WITH_USD
    if (options.displayTransformOn == "gpu")
        std::fprintf(stderr, "hdhair-record: warning: --displayTransformOn gpu needs --reader embedded (through "
                             "OpenUSD the plugin renders in its own context); the display transform runs on the "
                             "CPU\n");
    Complexity complexity = Complexity::Low;
    parseToken(options.complexity, &complexity);
    nlohmann::json allStats = nlohmann::json::array();
    PluginWarnings warnings;
    for (double time : timesToRender(options))
        allStats.push_back(recordFrameThroughUsdImaging(options, purposes, display, space, complexity, time, warnings));
    if (warnings.printed > kWarningsPrinted)
        std::fprintf(stderr, "hdhair-record: warning: %zu more warnings not shown (see --stats)\n",
                     warnings.printed - kWarningsPrinted);
    if (!options.statsFile.empty()) {
        nlohmann::json stats;
        stats["stage"] = options.usdFile;
        stats["frames"] = allStats;
        stats["warnings"] = warnings.warnings;
        writeTextFileAtomically(options.statsFile, stats.dump(2) + "\n");
        filesWritten.push_back(options.statsFile);
    }
    return 0;
#else
    (void)options;
    (void)purposes;
    (void)space;
    (void)display;
    throw std::invalid_argument("--reader usd needs hdHair built with OpenUSD (see README, 'Hydra plugin'); "
                                "this build has only --reader embedded");
#endif
}

// The end of an embedded or reference run: how many warnings were not
// printed, and --stats with every frame and every warning.
void finishRun(const Options& options, const nlohmann::json& allStats, const Diagnostics& diagnostics,
               size_t printed) {
    if (printed > kWarningsPrinted)
        std::fprintf(stderr, "hdhair-record: warning: %zu more warnings not shown (see --stats)\n",
                     printed - kWarningsPrinted);
    if (options.statsFile.empty()) return;
    nlohmann::json stats;
    stats["stage"] = options.usdFile;
    stats["frames"] = allStats;
    stats["warnings"] = nlohmann::json::array();
    for (const Diagnostic& warning : diagnostics.warnings())
        stats["warnings"].push_back({{"where", warning.where}, {"message", warning.message}});
    writeTextFileAtomically(options.statsFile, stats.dump(2) + "\n");
    filesWritten.push_back(options.statsFile);
}

// Set by SIGINT and SIGTERM while a reference renders: Blender is stopped
// and nothing is written (a farm's kill, or ^C).
std::atomic<bool> stopRequested{false};

void requestStop(int) { stopRequested.store(true); }

// --reference cycles' options, checked: throws std::invalid_argument for
// the first that is wrong, and warns that the display transform runs on the CPU.
void checkCyclesReferenceOptions(const Options& options) {
    if (options.reference != "cycles")
        throw std::invalid_argument("--reference must be cycles, not '" + options.reference + "'");
    if (options.readerGiven && options.reader != "embedded")
        throw std::invalid_argument("--reference cycles reads the stage with the embedded reader; leave out --reader "
                                    "or give --reader embedded");
    if (options.displayTransformOn == "gpu")
        std::fprintf(stderr, "hdhair-record: warning: --displayTransformOn gpu: a reference has no GL context; the "
                             "display transform runs on the CPU\n");
    const CyclesRenderOptions& cycles = options.cycles;
    if (cycles.samples < 1 || cycles.samples > 1 << 20) throw std::invalid_argument("--samples must be 1 to 1048576");
    if (cycles.maxBounces < 0 || cycles.maxBounces > 1024)
        throw std::invalid_argument("--maxBounces must be 0 (single scattering) to 1024");
    if (!(cycles.timeLimitSeconds >= 0.0)) throw std::invalid_argument("--timeLimit must be 0 (none) or more seconds");
}

// The request for one Cycles frame; its progress lines are timed from `lastReport`.
CyclesFrameRequest cyclesFrameRequest(const Options& options, Clock::time_point& lastReport) {
    CyclesFrameRequest request;
    request.blender = options.blender;
    request.options = options.cycles;
    request.stop = &stopRequested;
    request.progress = [&lastReport](const CyclesProgress& progress) {
        // One line every few seconds: a batch log stays readable.
        if (millisecondsSince(lastReport) < 2000.0 && progress.sample != progress.samples) return;
        lastReport = Clock::now();
        std::fprintf(stderr, "hdhair-record: cycles: sample %d/%d%s\n", progress.sample, progress.samples,
                     progress.secondsLeft >= 0.0 ? fmt::format(", {:.0f} s left", progress.secondsLeft).c_str()
                                                 : "");
    };
    return request;
}

// The reference render: what stays the same for every frame.
struct CyclesReferenceRun {
    const Options& options;
    const usda::SceneReadOptions& readOptions;
    const DisplayTransform& display;
    RenderingSpace space;
    const RenderSettings& settings;
    Diagnostics& diagnostics;
};

// One frame path-traced by Cycles and written as hdHair's own; returns its stats.
nlohmann::json renderCyclesReferenceFrame(const CyclesReferenceRun& run, const usda::Stage& stage, double time) {
    const Options& options = run.options;
    const RenderSettings& settings = run.settings;
    Diagnostics& diagnostics = run.diagnostics;
    const CyclesRenderOptions& cycles = options.cycles;
    Clock::time_point start = Clock::now();
    Scene scene;
    usda::readScene(stage, time, scene, diagnostics, run.readOptions);
    CyclesFraming framing;
    framing.camera = cameraPrimView(options, scene, diagnostics);
    framing.frame = [&](const SceneBounds& bounds) { return framingView(options, settings, scene, bounds); };
    const std::string outputPath =
        std::isfinite(time) ? expandFramePlaceholder(options.outputPath, time) : options.outputPath;
    if (options.verbose || options.explain)
        std::printf("hdhair-record: %s: Cycles reference: %d samples, seed %d, %d bounces%s\n",
                    describeTime(time).c_str(), cycles.samples, cycles.seed, cycles.maxBounces,
                    cycles.maxBounces == 0 ? " (single scattering)" : "");
    Clock::time_point lastReport = Clock::now();
    const CyclesFrameRequest request = cyclesFrameRequest(options, lastReport);
    CyclesFrame frame = renderCyclesFrame(scene, framing, settings, request, diagnostics);
    const CyclesProcessResult& result = frame.result;
    const CameraView& camera = frame.camera;
    if (options.verbose || options.explain)
        std::printf("hdhair-record: %s: exported %zu curves (%zu keys), %zu mesh triangles, %zu lights, %zu "
                    "domes\n",
                    describeTime(time).c_str(), frame.curves, frame.keys, frame.triangles, frame.lights,
                    frame.domes);
    const ImageMetadata metadata = cyclesFrameMetadata(cycles, result);
    std::vector<PassTiming> passes = {{"exportScene", frame.exportMilliseconds},
                                      {"cycles", result.renderSeconds * 1000.0}};
    nlohmann::json frameStats;
    writeFrameImage(std::move(frame.color), nullptr, run.display, run.space, outputPath, options.exrFloat32,
                    diagnostics, passes, frameStats, metadata);
    if (result.samplesDone < cycles.samples)
        diagnostics.warn(outputPath, fmt::format("Cycles stopped at the time limit after {} of {} samples",
                                                 result.samplesDone, cycles.samples));
    if (options.verbose || options.explain)
        std::printf("hdhair-record: %s: %dx%d, camera %s, %s, %d samples in %.1f s; wrote %s\n",
                    describeTime(time).c_str(), camera.imageWidth, camera.imageHeight,
                    cameraDescription(options, settings).c_str(), result.blenderVersion.c_str(),
                    result.samplesDone, result.renderSeconds, outputPath.c_str());
    frameStats["reference"] = "cycles";
    frameStats["scene"] = frame.scene;
    frameStats["samplesDone"] = result.samplesDone;
    frameStats["camera"] = cameraDescription(options, settings);
    frameStats["time"] = std::isfinite(time) ? nlohmann::json(time) : nlohmann::json(describeTime(time));
    frameStats["output"] = outputPath;
    for (const PassTiming& pass : passes)
        frameStats["passes"].push_back({{"name", pass.name}, {"milliseconds", pass.milliseconds}});
    frameStats["totalMilliseconds"] = millisecondsSince(start);
    return frameStats;
}

// --reference cycles: each frame's scene, read by the embedded reader and
// prepared as hdHair prepares it, exported once and path-traced by Cycles;
// the image is written as hdHair's own (colour space, alpha, atomic write),
// the EXR with the path tracer's settings in its metadata.
int runCyclesReference(const Options& options, const usda::SceneReadOptions& readOptions,
                       const DisplayTransform& display, RenderingSpace space, const RenderSettings& settings) {
    checkCyclesReferenceOptions(options);
    Diagnostics diagnostics;
    size_t printed = 0;
    diagnostics.setListener([&](const Diagnostic& warning) {
        if (printed++ < kWarningsPrinted)
            std::fprintf(stderr, "hdhair-record: warning: %s: %s\n", warning.where.c_str(), warning.message.c_str());
    });
    std::unique_ptr<usda::Stage> stage = usda::Stage::open(options.usdFile);
    std::signal(SIGINT, requestStop);
    std::signal(SIGTERM, requestStop);
    const CyclesReferenceRun run{options, readOptions, display, space, settings, diagnostics};
    nlohmann::json allStats = nlohmann::json::array();
    for (double time : timesToRender(options)) allStats.push_back(renderCyclesReferenceFrame(run, *stage, time));
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    finishRun(options, allStats, diagnostics, printed);
    return 0;
}

// --check: what every frame's render would refuse, found without rendering:
// the arguments, the output targets, the stage (read by the embedded reader,
// which needs no GL) and the camera at the first frame. Prints, as JSON, the
// stage, the output pattern, the frames and the images' size, which
// hdhair-farm uses to tell a complete frame from one to render again.
// A problem at a later frame only (an animated camera that breaks at frame 7)
// is that frame's error when it renders.
int checkInput(const Options& options, const usda::SceneReadOptions& readOptions, const RenderSettings& settings) {
    Diagnostics diagnostics;
    const std::unique_ptr<usda::Stage> stage = usda::Stage::open(options.usdFile);
    const std::vector<double> times = timesToRender(options);
    Scene scene;
    usda::readScene(*stage, times.front(), scene, diagnostics, readOptions);
    std::optional<CameraView> camera = cameraPrimView(options, scene, diagnostics);
    // The framing camera's image shape is its aperture's, whatever bounds it
    // frames: unit bounds stand in for the scene's, which need GL to measure.
    if (!camera) camera = framingView(options, settings, scene, SceneBounds{glm::dvec3(-1.0), glm::dvec3(1.0)});
    nlohmann::json report;
    report["stage"] = options.usdFile;
    report["output"] = options.outputPath;
    report["frames"] = nlohmann::json::array();
    for (double time : times) report["frames"].push_back(std::isfinite(time) ? nlohmann::json(time) : nlohmann::json());
    report["imageWidth"] = camera->imageWidth;
    report["imageHeight"] = camera->imageHeight;
    report["warnings"] = nlohmann::json::array();
    for (const Diagnostic& warning : diagnostics.warnings())
        report["warnings"].push_back(warning.where + ": " + warning.message);
    std::printf("%s\n", report.dump().c_str());
    return 0;
}

// The settings a run renders with, after the checks every path shares:
// --complexity, --quality, --imageWidth, the output's extension and
// placeholder, the outputs' folders. Throws std::invalid_argument with the
// reason.
RenderSettings checkedSettings(const Options& options) {
    Complexity complexity;
    if (!parseToken(options.complexity, &complexity))
        throw std::invalid_argument("--complexity must be " + tokenChoices<Complexity>());
    if (Quality quality; !options.quality.empty() && !parseToken(options.quality, &quality))
        throw std::invalid_argument("--quality must be " + tokenChoices<Quality>() + ", not '" + options.quality + "'");
    RenderSettings settings = RenderSettings::fromAssignments(complexity, settingAssignments(options));
    const RenderSettings asked = RenderSettings::fromAssignments(complexity, options.settings);
    if (asked.values().interactiveBudgetMs != 0 && asked.isExplicitlySet("interactiveBudgetMs"))
        std::fprintf(stderr, "hdhair-record: warning: interactiveBudgetMs=%d has no effect here: it sets the previews "
                             "interactive Hydra hosts (usdview) show, and hdhair-record writes full frames only\n",
                     asked.values().interactiveBudgetMs);
    if (options.imageWidth < 1 || options.imageWidth > 16384)
        throw std::invalid_argument("--imageWidth must be between 1 and 16384");
    if (!isSupportedImagePath(options.outputPath))
        throw std::invalid_argument("cannot write '" + options.outputPath +
                                    "': unsupported image extension (use .exr, .png, .tif, .tiff, .jpg or .jpeg)");
    return settings;
}

// The embedded reader's render: what stays the same for every frame.
struct EmbeddedRun {
    const Options& options;
    const RenderSettings& settings;
    const DisplayTransform& display;
    RenderingSpace space;
    usda::SceneReadOptions readOptions;
    Renderer& renderer;
    DisplayShader displayShader;  // --displayTransformOn gpu
    Diagnostics& diagnostics;
};

// --verbose and --explain for one frame: the plans, the passes' times and
// what was drawn.
void printFrameReport(const EmbeddedRun& run, double time, const CameraView& camera, const std::string& cameraName,
                      const RenderResult& result, const std::string& outputPath) {
    const Options& options = run.options;
    if (options.explain) printSettingOrigins(run.settings);
    if (options.explain)
        std::printf("hdhair-record: plan (%s):\n%s", describeTime(time).c_str(), result.describePlans().c_str());
    if (!options.verbose && !options.explain) return;
    std::string passes;
    for (const PassTiming& pass : result.stats.passes)
        passes += fmt::format("{}{} {:.1f} ms", passes.empty() ? "" : ", ", pass.name, pass.milliseconds);
    std::string programs;
    for (const std::string& shading : result.stats.strandShaders)
        programs += fmt::format("{}[{}]", programs.empty() ? "" : ", ", shading);
    std::printf("hdhair-record: %s: %dx%d, camera %s, %llu curves, %llu segments, %llu strand triangles"
                "; %s; strand %s; strand programs %s; wrote %s\n",
                describeTime(time).c_str(), camera.imageWidth, camera.imageHeight, cameraName.c_str(),
                static_cast<unsigned long long>(result.stats.curves),
                static_cast<unsigned long long>(result.stats.segments),
                static_cast<unsigned long long>(result.stats.strandTriangles), passes.c_str(),
                result.stats.drawBatching.c_str(), programs.empty() ? "none" : programs.c_str(), outputPath.c_str());
}

// One frame through the embedded reader: the stage at `time` into `scene`
// (prims that did not change keep their versions, so they are not prepared
// or uploaded again), rendered and written. Returns its stats.
nlohmann::json renderEmbeddedFrame(EmbeddedRun& run, const usda::Stage& stage, Scene& scene, double time) {
    const Options& options = run.options;
    Diagnostics& diagnostics = run.diagnostics;
    Clock::time_point sceneStart = Clock::now();
    Scene atTime;
    usda::readScene(stage, time, atTime, diagnostics, run.readOptions);
    scene.updateFrom(atTime);
    double sceneMilliseconds = millisecondsSince(sceneStart);

    std::optional<CameraView> chosen = cameraPrimView(options, scene, diagnostics);
    CameraView camera = chosen ? *chosen
                               : framingView(options, run.settings, scene,
                                             run.renderer.prepare(scene, run.settings, diagnostics));
    const std::string cameraName = cameraDescription(options, run.settings);

    const bool gpuDisplay = options.displayTransformOn == "gpu" && !isSceneLinearImagePath(options.outputPath);
    RenderOutputs outputs;
    outputs.gpuDisplay = gpuDisplay ? &run.displayShader : nullptr;
    outputs.displayOverBlack = !keepsAlpha(options.outputPath);
    outputs.depth = false;  // only colour is written
    RenderResult result = run.renderer.render(scene, camera, run.settings, diagnostics, outputs);
    if (std::string why = whyNothingDrawn(scene, result, diagnostics.warningCount()); !why.empty())
        diagnostics.warn(options.usdFile, why);
    result.stats.camera = cameraName;
    result.stats.time = time;
    result.stats.passes.insert(result.stats.passes.begin(), PassTiming{"readScene", sceneMilliseconds});

    std::string outputPath =
        std::isfinite(time) ? expandFramePlaceholder(options.outputPath, time) : options.outputPath;
    nlohmann::json frameColor;
    writeFrameImage(std::move(result.color), gpuDisplay ? &result.display : nullptr, run.display, run.space,
                    outputPath, options.exrFloat32, diagnostics, result.stats.passes, frameColor);
    printFrameReport(run, time, camera, cameraName, result, outputPath);
    nlohmann::json frameStats = result.stats.toJson();
    frameStats["output"] = outputPath;
    frameStats["color"] = frameColor["color"];
    return frameStats;
}

// --reader embedded: hdHair's own .usda reader and renderer, every frame.
int runEmbedded(const Options& options, const RenderSettings& settings, gl::GlBackend backend,
                const usda::SceneReadOptions& readOptions, const DisplayTransform& display, RenderingSpace space) {
    Diagnostics diagnostics;
    size_t printed = 0;
    diagnostics.setListener([&](const Diagnostic& warning) {
        if (printed++ < kWarningsPrinted)
            std::fprintf(stderr, "hdhair-record: warning: %s: %s\n", warning.where.c_str(), warning.message.c_str());
    });
    Clock::time_point readStart = Clock::now();
    std::unique_ptr<usda::Stage> stage = usda::Stage::open(options.usdFile);
    double readMilliseconds = millisecondsSince(readStart);

    Renderer renderer(backend);
    EmbeddedRun run{options, settings, display, space, readOptions, renderer, {}, diagnostics};
    if (options.displayTransformOn == "gpu") run.displayShader = display.shader();
    if (options.verbose)
        std::printf("hdhair-record: GL %s (%s) on %s; read %s in %.1f ms\n", gl::toString(backend),
                    renderer.glDescription().c_str(), renderer.glDevice().c_str(), options.usdFile.c_str(),
                    readMilliseconds);
    nlohmann::json allStats = nlohmann::json::array();
    Scene scene;
    for (double time : timesToRender(options)) allStats.push_back(renderEmbeddedFrame(run, *stage, scene, time));
    finishRun(options, allStats, diagnostics, printed);
    return 0;
}

int run(const Options& options) {
    const RenderSettings settings = checkedSettings(options);
    gl::GlBackend backend = gl::defaultGlBackend();
    if (!options.gl.empty() && !gl::parseGlBackend(options.gl, &backend))
        throw std::invalid_argument("--gl must be egl or osmesa");
    checkOutputTargets(options);
    if (const size_t frames = timesToRender(options).size(); frames > 1 && !hasFramePlaceholder(options.outputPath))
        throw std::invalid_argument("rendering " + std::to_string(frames) +
                                    " frames needs a '#' placeholder in the output name, e.g. out.####.png");
    usda::SceneReadOptions readOptions = purposesFrom(options.purposes);
    const RenderingSpace space = settings.renderingSpace();
    const DisplayTransform display = displayTransformFor(options, space);
    if (options.check) return checkInput(options, readOptions, settings);
    if (!options.reference.empty()) return runCyclesReference(options, readOptions, display, space, settings);
    if (options.reader == "usd") return runThroughUsdImaging(options, readOptions, display, space);
    if (options.reader != "embedded") throw std::invalid_argument("--reader must be usd or embedded");
    return runEmbedded(options, settings, backend, readOptions, display, space);
}

}  // namespace

// The settings reference as a Markdown table, from the descriptors
// (docs/settings.md holds it; testHdhairRecord keeps the two equal).
static std::string settingsMarkdown() {
    const auto cell = [](const std::string& text) {
        std::string escaped;
        for (char c : text) escaped += c == '|' ? std::string("\\|") : std::string(1, c);
        return escaped;
    };
    const auto number = [](double value) { return fmt::format("{:g}", value); };
    std::string text = "| setting | values | default | meaning |\n|---|---|---|---|\n";
    for (const SettingDescriptor& descriptor : RenderSettings::descriptors()) {
        std::string values;
        if (!descriptor.tokens.empty()) {
            for (const std::string& token : descriptor.tokens) values += (values.empty() ? "" : ", ") + ("`" + token + "`");
        } else if (descriptor.type == SettingType::Bool) {
            values = "`true`, `false`";
        } else if (descriptor.type == SettingType::Int || descriptor.type == SettingType::Float) {
            values = fmt::format("{} {} to {}", descriptor.type == SettingType::Int ? "integer" : "number",
                                 number(descriptor.minimum), number(descriptor.maximum));
        } else {
            values = "text";
        }
        text += fmt::format("| `{}` | {} | `{}` | {} |\n", descriptor.name, values, cell(descriptor.defaultValue),
                            cell(descriptor.description));
    }
    return text;
}

namespace {

// The stage, the camera, the frames and what is rendered.
void addRenderOptions(CLI::App& app, Options& options) {
    app.add_option("usdFile", options.usdFile, "The stage to render (.usda)")->required();
    app.add_option("outputImagePath", options.outputPath,
                   "Output image (.exr: scene-linear half float; .png/.tif/.jpg: 8-bit through the display "
                   "transform). A '#' run is replaced "
                   "by the frame number")
        ->required();
    app.add_option("--camera", options.camera,
                   "Camera prim path; without it, a camera framing the whole stage is used");
    app.add_option("--imageWidth,-w", options.imageWidth,
                   "Image width in pixels; the height follows the camera's aspect ratio")
        ->capture_default_str();
    auto* frames = app.add_option("--frames,-f", options.frames,
                                  "Frames to render: 12, 1:10, 1:10x2, or a comma-separated list");
    app.add_flag("--defaultTime,-d", options.defaultTime,
                 "Render at the Default time code (otherwise the earliest time)")
        ->excludes(frames);
    app.add_option("--complexity,-c", options.complexity, "Tessellation density: low, medium, high, veryhigh")
        ->capture_default_str();
    app.add_option("--quality,-q", options.quality,
                   "Quality preset: preview, default, high or reference (README, Quality presets); --setting and "
                   "a complexity above low win over it");
    app.add_option("--setting,-s", options.settings,
                   "A renderer setting NAME=VALUE (repeatable); --help-settings lists them");
    app.add_option("--purposes", options.purposes,
                   "Purposes rendered besides 'default': comma-separated render, proxy, guide")
        ->capture_default_str();
    app.add_option("--gl", options.gl, "OpenGL context: egl (default, or $HDHAIR_GL) or osmesa");
    app.add_option("--reader", options.reader,
                   "How the stage is read: usd (OpenUSD, UsdImaging and the HdHair plugin, when built with "
                   "OpenUSD) or embedded (hdHair's own .usda reader)")
        ->capture_default_str();
}

// How the image is written and what the run reports.
void addOutputOptions(CLI::App& app, Options& options) {
    app.add_option("--colorCorrectionMode,--color", options.colorCorrectionMode,
                   "Display transform of .png/.tif/.jpg outputs: disabled, sRGB or openColorIO (EXR stays "
                   "scene-linear)")
        ->capture_default_str();
    app.add_option("--ocioConfig", options.ocioConfig,
                   "OCIO config for openColorIO (default: $OCIO, else hdHair's own)");
    app.add_option("--ocioDisplay", options.ocioDisplay, "OCIO display (default: the config's default)");
    app.add_option("--ocioView", options.ocioView, "OCIO view (default: the display's default)");
    app.add_option("--ocioColorSpace", options.ocioColorSpace,
                   "The rendered image's colour space (default: the rendering space, lin_rec709)");
    app.add_option("--ocioLook", options.ocioLook, "OCIO look applied before the view");
    app.add_option("--displayTransformOn", options.displayTransformOn,
                   "Where the display transform runs: cpu (OpenColorIO's CPU processor) or gpu (its GLSL, on "
                   "hdHair's GL context)")
        ->capture_default_str();
    app.add_flag("--exrFloat32", options.exrFloat32,
                 "Write .exr as 32-bit floats, every value exactly (default: half floats, values beyond 65504 "
                 "clamped with a warning)");
    app.add_option("--stats", options.statsFile, "Write what was rendered (prims, curves, segments, pass times, "
                                                 "settings) to this JSON file");
    app.add_flag("--verbose,-v", options.verbose, "Print what was done and how long each pass took");
    app.add_flag("--explain", options.explain, "Print the render plan: which passes run and why");
    app.add_flag("--check", options.check,
                 "Check the arguments, outputs, stage and camera (at the first frame) as a render would, render "
                 "nothing, and print the frames and image size as JSON (hdhair-farm runs it before submitting)");
}

// --reference cycles and its options.
void addReferenceOptions(CLI::App& app, Options& options) {
    app.add_option("--reference", options.reference,
                   "Render a path-traced reference instead: cycles (Blender's Cycles, headless; the stage is read "
                   "by the embedded reader and exported as hdHair prepares it; docs/cycles-reference.md)");
    app.add_option("--samples", options.cycles.samples, "--reference: samples per pixel")->capture_default_str();
    app.add_option("--seed", options.cycles.seed, "--reference: Cycles' sampling seed")->capture_default_str();
    app.add_option("--maxBounces", options.cycles.maxBounces,
                   "--reference: scattering events after the first (0: single scattering)")
        ->capture_default_str();
    app.add_option("--timeLimit", options.cycles.timeLimitSeconds,
                   "--reference: stop after this many seconds (0: none), at the sample reached")
        ->capture_default_str();
    app.add_option("--blender", options.blender, "--reference: the Blender executable")->capture_default_str();
}

// --help-settings [--format text|markdown], which needs no positional
// arguments: the exit status when it was asked for.
std::optional<int> listSettingsIfAsked(int argc, char** argv) {
    bool asked = false;
    std::string format = "text";
    for (int i = 1; i < argc; ++i) {
        asked = asked || std::string(argv[i]) == "--help-settings";
        if (std::string(argv[i]) == "--format" && i + 1 < argc) format = argv[i + 1];
    }
    if (!asked) return std::nullopt;
    if (format == "markdown") {
        std::printf("%s", settingsMarkdown().c_str());
        return 0;
    }
    if (format != "text") {
        std::fprintf(stderr, "hdhair-record: error: --format must be text or markdown, not '%s'\n", format.c_str());
        return 2;
    }
    for (const SettingDescriptor& descriptor : RenderSettings::descriptors())
        std::printf("%-22s default %-8s %s\n", descriptor.name.c_str(), descriptor.defaultValue.c_str(),
                    descriptor.description.c_str());
    return 0;
}

// run(), with each failure one line and its exit status: 1 for the input,
// 75 for the machine (out of memory, no GL).
int runReportingFailures(const Options& options) {
    try {
        return run(options);
    } catch (const std::bad_alloc&) {
        removeFilesWritten();
        std::fprintf(stderr, "hdhair-record: error: out of memory (std::bad_alloc); lower --imageWidth, supersampling "
                             "or exactMemoryMB, or render on a machine with more memory\n");
        return kMachineFailed;
    } catch (const gl::GlUnavailableError& error) {
        removeFilesWritten();
        std::fprintf(stderr, "hdhair-record: error: %s\n", error.what());
        return kMachineFailed;
    } catch (const std::exception& error) {
        removeFilesWritten();
        std::fprintf(stderr, "hdhair-record: error: %s\n", error.what());
        return 1;
    }
}

}  // namespace

int main(int argc, char** argv) {
    Options options;
    CLI::App app{"Renders a USD stage's hair curves to images, like usdrecord, with hdHair's engine.",
                 "hdhair-record"};
    addRenderOptions(app, options);
    addOutputOptions(app, options);
    addReferenceOptions(app, options);
    // Listed in --help; listSettingsIfAsked answers them before parsing.
    bool listSettings = false;
    std::string settingsFormat = "text";
    app.add_flag("--help-settings", listSettings, "List the renderer settings with defaults and exit");
    app.add_option("--format", settingsFormat,
                   "--help-settings: text, or markdown (the table of docs/settings.md, which a test keeps equal)")
        ->capture_default_str();
    if (std::optional<int> status = listSettingsIfAsked(argc, argv)) return *status;
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& help) {
        return app.exit(help);
    } catch (const CLI::ParseError& error) {
        std::fprintf(stderr, "hdhair-record: error: %s (see --help)\n", error.what());
        return 2;
    }
    options.readerGiven = app.count("--reader") > 0;
    options.framesGiven = app.count("--frames") > 0;
    return runReportingFailures(options);
}
