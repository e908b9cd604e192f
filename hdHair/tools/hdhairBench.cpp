// hdhair-bench: what accuracy costs in time, measured with Google Benchmark.
//
//   hdhair-bench [--stage FILE]... [--imageWidth N]
//                [--table complexity|transparency|shading|shadows|tessellation|all] [Google Benchmark flags]
//   hdhair-bench --table dome [--domeTexture FILE] [--repetitions N] [--stage FILE]... [--imageWidth N]
//   hdhair-bench --accuracy [--quick] [--out DIR] [--repetitions N] [--stage FILE]... [--imageWidth N]
//                [--cycles [--cyclesSamples N] [--cyclesBlock PX] [--blender EXE]]
//   hdhair-bench --report accuracy.json [--out DIR]   (an earlier report's front and tables again)
//   hdhair-bench --help   (every option; unknown arguments are an error)
//
// --accuracy: the error-versus-time matrix of every approximation and quality
// preset against each stage's reference (AccuracyBench.h), written to DIR
// (default accuracy/) as accuracy.json, .csv and .md with the Pareto front
// marked (AccuracyReport.h); its checks (AccuracyChecks.h) are printed, and
// with --quick (the CI run: short ladders, one repetition, 64 pixels wide)
// a failed check is exit status 1 (not with --cycles, below). scripts/accuracy-bench.sh runs the full
// matrix and draws the plots. --cycles adds Blender's Cycles as the outside
// reference (--cyclesSamples per pixel, default 256; errors over blocks of
// --cyclesBlock pixels, default 16), every frame shaded with Marschner, and
// writes the Cycles frames beside the report as <stage>.cycles-*.exr.
//
// For each stage (examples/dense_clump.usda when none is given), rendered
// through its first camera (or a framing camera):
//   ParseLayer/5 MB                     the embedded reader on a 5 MB layer of curves
//   SrbfFit/1024x512                    a 1k latlong dome texture (a procedural sky, half EXR) read
//                                       onto the 64 × 32 grid and fitted with 30 SRBF lights
//                                       (hdHair/environment: the issue asks for well under a second)
//   ComposeStage/<n> prims              composing n small sibling prims (counts: testUsdaReader)
//   SrbfTables/Build/<kind>             building one SRBF-convolution table at the default
//                                       resolution (hdHair/shading/SrbfConvolutionTables.h)
//   PrepareCurves/<stage>               CPU curve preparation
//   BinSort/<stage>                     the CPU bin sort of the frame's segments
//   RenderFrame/<stage>/<complexity>    a frame per --complexity level
//   RenderFrame/<stage>/<transparency>  a frame per transparency mode and bin count
//   RenderFrame/<stage>/<model> <n> lights  a frame per shading model and light count
//   ShadowFrame/<stage>/<shadows>       a frame that rebuilds every light's shadow (each
//                                       light turned by a microradian), per shadowLayers,
//                                       shadowMapResolution, filter and spacing, timed in
//                                       process CPU seconds (llvmpipe's threads included)
// --table dome: the SRBF dome lighting against its reference and its cost
// (DomeBench.h), under --domeTexture (default examples/dome_sky.exr), 128
// pixels wide unless --imageWidth says otherwise; no Google Benchmark runs.
// Then it prints markdown tables: each configuration's time relative to a
// reference measured in the same run (these machines are shared and noisy,
// so ratios mean more than milliseconds), and its image error against the
// most accurate configuration (RMSE and largest difference, pre-multiplied
// linear RGBA, over the pixels either image covers: hdHair/image/ImageComparison.h).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <sys/resource.h>
#include <unistd.h>

#include <benchmark/benchmark.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <fmt/format.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/base/RegularFile.h"
#include "hdHair/curves/PreparedCurves.h"
#include "hdHair/environment/DomeTextureFitCache.h"
#include "hdHair/environment/LatlongDirections.h"
#include "hdHair/environment/LatlongTexture.h"
#include "hdHair/image/BoxDownsample.h"
#include "hdHair/image/ImageComparison.h"
#include "hdHair/image/ImageWriter.h"
#include "hdHair/shading/MarschnerTables.h"
#include "hdHair/shading/SrbfConvolutionTables.h"
#include "hdHair/bench/AccuracyBench.h"
#include "hdHair/bench/AccuracyChecks.h"
#include "hdHair/bench/AccuracyReport.h"
#include "hdHair/bench/BenchLights.h"
#include "hdHair/render/BinSort.h"
#include "hdHair/plan/CameraView.h"
#include "hdHair/render/Renderer.h"
#include "hdHair/scene/Scene.h"
#include "hdHair/bench/DomeBench.h"
#include "hdHair/usda/SceneReader.h"
#include "hdHair/usda/Stage.h"
#include "hdHair/usda/tests/SyntheticLayers.h"

namespace {

using namespace hdhair;

// One step of an 8-bit image: the "pixels over 1/255" column counts covered
// pixels further apart.
constexpr double kOneStep = 1.0 / 255.0;

struct Configuration {
    std::string label;                  // "binSorted 256", "high"
    std::vector<std::string> settings;  // NAME=VALUE
    Complexity complexity = Complexity::Low;
};

struct BenchStage;
void setLightCount(BenchStage& stage, int count);

struct BenchStage {
    std::string path, name;
    Scene scene;
    CameraView camera;
    // Every prim's curves and sort hashes, sorted together as a frame sorts them.
    std::vector<PreparedCurves> prepared;
    std::vector<std::vector<uint16_t>> sortHashes;
    std::vector<SortSpan> sortSpans;
    size_t segments = 0;
    std::vector<LightPrim> stageLights;             // as authored, for the light-count benchmarks
};

constexpr int kStageLights = -1;  // the stage's own lights, as authored

// Gives the stage `count` distant lights of equal total irradiance, spread
// around the camera's hemisphere, or (kStageLights) its own lights back.
void setLightCount(BenchStage& stage, int count) {
    std::vector<std::string> paths;
    for (const auto& [path, entry] : stage.scene.lights()) paths.push_back(path);
    for (const std::string& path : paths) stage.scene.remove(path);
    if (count == kStageLights)
        for (const LightPrim& light : stage.stageLights) stage.scene.setLight(light);
    for (int i = 0; i < count; ++i) {
        LightPrim light;
        light.path = "/BenchLights/light" + std::to_string(i);
        light.intensity = 2.0f / float(count);
        double azimuth = 6.283185307179586 * i / count, elevation = 0.3 + 0.5 * ((i * 7) % count) / count;
        glm::dvec3 towards(std::cos(azimuth) * std::cos(elevation), std::sin(elevation),
                           std::sin(azimuth) * std::cos(elevation));
        glm::dvec3 z = glm::normalize(towards);
        glm::dvec3 x = glm::normalize(glm::cross(glm::dvec3(0, 1, 0), z));
        light.worldTransform = glm::dmat4(glm::dvec4(x, 0), glm::dvec4(glm::cross(z, x), 0), glm::dvec4(z, 0),
                                          glm::dvec4(0, 0, 0, 1));
        stage.scene.setLight(light);
    }
}

std::unique_ptr<Renderer>& renderer() {
    static std::unique_ptr<Renderer> instance;
    return instance;
}

RenderSettings settingsFor(const Configuration& configuration) {
    return RenderSettings::fromAssignments(configuration.complexity, configuration.settings);
}

std::vector<Configuration> complexityConfigurations() {
    std::vector<Configuration> result;
    for (Complexity level : {Complexity::Low, Complexity::Medium, Complexity::High, Complexity::VeryHigh})
        result.push_back({toString(level), {}, level});
    return result;
}

struct ShadingConfiguration {
    std::string model;  // the table's row
    Configuration configuration;
    int lights;
};

std::string frameName(const BenchStage& stage, const Configuration& configuration);

// A frame benchmark: the stage with `lights` (or kStageLights) under a configuration.
void registerFrame(BenchStage* stage, const Configuration& configuration, int lights) {
    benchmark::RegisterBenchmark(frameName(*stage, configuration).c_str(),
                                 [stage, configuration, lights](benchmark::State& state) {
                                     setLightCount(*stage, lights);
                                     RenderSettings settings = settingsFor(configuration);
                                     Diagnostics diagnostics;
                                     for (auto _ : state)
                                         benchmark::DoNotOptimize(
                                             renderer()->render(stage->scene, stage->camera, settings, diagnostics)
                                                 .color.pixels.data());
                                 })
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
}

std::vector<ShadingConfiguration> shadingConfigurations() {
    std::vector<ShadingConfiguration> result;
    const std::pair<const char*, std::vector<std::string>> models[] = {
        {"flat", {"shadingModel=flat"}},
        {"kajiyaKay", {"shadingModel=kajiyaKay"}},
        {"marschner (tables)", {"shadingModel=marschner", "marschner:azimuthal=tables"}},
        {"marschner (auto)", {"shadingModel=marschner", "marschner:azimuthal=auto"}},
        {"marschner (analytic)", {"shadingModel=marschner", "marschner:azimuthal=analytic"}},
    };
    for (const auto& [model, settings] : models)
        for (int lights : {1, 4, 8, 16})
            result.push_back({model, {fmt::format("{} {} lights", model, lights), settings, Complexity::Low}, lights});
    return result;
}

std::vector<Configuration> transparencyConfigurations() {
    std::vector<Configuration> result = {{"opaque", {"transparency=opaque"}, Complexity::Low},
                                         {"unsorted", {"transparency=unsorted"}, Complexity::Low}};
    for (int bins : {1, 16, 64, 256, 1024})
        result.push_back({fmt::format("binSorted {}", bins),
                          {"transparency=binSorted", fmt::format("sortBins={}", bins)},
                          Complexity::Low});
    result.push_back({"exact", {"transparency=exact", "exactMemoryMB=2048"}, Complexity::Low});
    return result;
}

// Shadows: off (the time reference); deep opacity maps over layers and
// resolutions; around the defaults (3 layers, 1024 texels), layer depth,
// filter, spacing, and how the light views rasterise strand lines (in
// compute, or drawn by GL, shadowStrandLines); and the reference (the error
// yardstick, at the finest resolution). Every row names all its settings,
// so the table does not depend on the defaults.
std::vector<Configuration> shadowConfigurations() {
    std::vector<Configuration> result = {{"off", {"shadowMode=off"}, Complexity::Low}};
    auto add = [&](int layers, int resolution, const char* depth, const char* filter, const char* spacing,
                   const char* lines = "compute") {
        result.push_back({fmt::format("{} layers, {}, depth {}, {}{}{}", layers, resolution, depth, filter,
                                      std::string(spacing) == "linear" ? "" : ", uniform spacing",
                                      std::string(lines) == "compute" ? "" : fmt::format(", lines {}", lines)),
                          {fmt::format("shadowLayers={}", layers), fmt::format("shadowMapResolution={}", resolution),
                           std::string("shadowLayerDepth=") + depth, std::string("shadowFilter=") + filter,
                           std::string("shadowLayerSpacing=") + spacing, std::string("shadowStrandLines=") + lines},
                          Complexity::Low});
    };
    for (int resolution : {512, 1024, 2048, 4096})
        for (int layers : {3, 7, 15}) add(layers, resolution, "1", "bilinear", "linear");
    for (const char* depth : {"0.5", "0.25", "0.1"}) add(3, 1024, depth, "bilinear", "linear");
    add(3, 1024, "1", "nearest", "linear");
    add(3, 1024, "1", "bilinear", "uniform");
    for (int resolution : {512, 1024})
        for (const char* lines : {"drawn", "tessellated"}) add(3, resolution, "1", "bilinear", "linear", lines);
    result.push_back({"reference, 4096", {"shadowMode=reference", "shadowMapResolution=4096"}, Complexity::Low});
    return result;
}

// Turns every light of the stage by +-1 microradian about Y: each light's
// view changes, so a frame rebuilds every shadow, as after a light moved.
void nudgeLights(BenchStage& stage, bool forth) { turnLightsAboutY(stage.scene, forth ? 1e-6 : -1e-6); }

std::string shadowFrameName(const BenchStage& stage, const Configuration& configuration) {
    return "ShadowFrame/" + stage.name + "/" + configuration.label;
}

// Seconds of CPU this process has used, llvmpipe's rendering threads
// included: the work a frame costs, which other load on a shared machine
// changes far less than it changes wall-clock time.
double processCpuSeconds() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    auto seconds = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
    return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

// CPU seconds of one frame.
double frameCpuSeconds(BenchStage& stage, const RenderSettings& settings, Diagnostics& diagnostics) {
    const double start = processCpuSeconds();
    benchmark::DoNotOptimize(renderer()->render(stage.scene, stage.camera, settings, diagnostics).color.pixels.data());
    return processCpuSeconds() - start;
}

// Timed in process CPU seconds (manual time), each iteration a frame that
// rebuilds every shadow.
void registerShadowFrame(BenchStage* stage, const Configuration& configuration) {
    benchmark::RegisterBenchmark(shadowFrameName(*stage, configuration).c_str(),
                                 [stage, configuration](benchmark::State& state) {
                                     setLightCount(*stage, kStageLights);
                                     RenderSettings settings = settingsFor(configuration);
                                     Diagnostics diagnostics;
                                     bool forth = true;
                                     for (auto _ : state) {
                                         nudgeLights(*stage, forth = !forth);
                                         state.SetIterationTime(frameCpuSeconds(*stage, settings, diagnostics));
                                     }
                                 })
        ->Unit(benchmark::kMillisecond)
        ->UseManualTime();
}

// Keeps each run's time so the tables can relate them.
class RecordingReporter : public benchmark::ConsoleReporter {
public:
    void ReportRuns(const std::vector<Run>& runs) override {
        // With --benchmark_repetitions the median stands for the benchmark.
        for (const Run& run : runs) {
            const std::string& name = run.run_name.function_name;
            if (run.run_type == Run::RT_Iteration && !medians.count(name)) seconds[name] = run.GetAdjustedRealTime();
            if (run.run_type == Run::RT_Aggregate && run.aggregate_name == "median") {
                seconds[name] = run.GetAdjustedRealTime();
                medians.insert(name);
            }
        }
        ConsoleReporter::ReportRuns(runs);
    }
    std::map<std::string, double> seconds;  // by benchmark name, in the benchmark's unit (milliseconds)
    std::set<std::string> medians;          // names whose time is a median of repetitions
};

std::string frameName(const BenchStage& stage, const Configuration& configuration) {
    return "RenderFrame/" + stage.name + "/" + configuration.label;
}

void printTable(const BenchStage& stage, const std::vector<Configuration>& configurations, size_t reference,
                size_t timeReference, const RecordingReporter& reporter, const char* title) {
    Diagnostics diagnostics;
    RenderResult best = renderer()->render(stage.scene, stage.camera, settingsFor(configurations[reference]),
                                           diagnostics);
    std::printf("\n%s, %s (%dx%d, %llu segments): time relative to %s, error against %s%s\n\n", title,
                stage.path.c_str(), stage.camera.imageWidth, stage.camera.imageHeight,
                static_cast<unsigned long long>(best.stats.segments), configurations[timeReference].label.c_str(),
                configurations[reference].label.c_str(),
                best.stats.fallback.empty() ? "" : (" (" + best.stats.fallback + ")").c_str());
    std::printf("| configuration | path taken | time | RMSE | max difference |\n|---|---|---|---|---|\n");
    auto base = reporter.seconds.find(frameName(stage, configurations[timeReference]));
    for (const Configuration& configuration : configurations) {
        RenderResult result = renderer()->render(stage.scene, stage.camera, settingsFor(configuration), diagnostics);
        ImageComparison difference = compareImages(result.color, best.color, exactWithin(kOneStep));
        auto time = reporter.seconds.find(frameName(stage, configuration));
        std::string ratio = (time != reporter.seconds.end() && base != reporter.seconds.end())
                                ? fmt::format("{:.2f}x", time->second / base->second)
                                : "not run";
        std::printf("| %s | %s | %s | %.5f | %.4f |\n", configuration.label.c_str(), result.stats.transparency.c_str(),
                    ratio.c_str(), difference.rootMeanSquare, difference.maxDifference);
    }
}

// Per shadow configuration, in process CPU seconds: a frame that rebuilds
// every light's shadow (Google Benchmark, median of the run's repetitions)
// relative to one with shadows off, and the shadow passes' share, that frame
// less one that keeps its maps (the fastest of three); then the image's
// error against the reference. '*' marks the error-versus-time Pareto front:
// nothing else is both cheaper and closer to the reference.
void printShadowTable(BenchStage& stage, const std::vector<Configuration>& configurations,
                      const RecordingReporter& reporter) {
    Diagnostics diagnostics, referenceDiagnostics;
    setLightCount(stage, kStageLights);
    const size_t off = 0, reference = configurations.size() - 1;
    RenderResult best = renderer()->render(stage.scene, stage.camera, settingsFor(configurations[reference]),
                                           referenceDiagnostics);
    std::printf("\nShadows, %s (%dx%d, %llu segments, %zu shadow-casting lights): process CPU time of a frame "
                "that rebuilds every shadow, relative to shadows off; error against %s%s\n\n",
                stage.path.c_str(), stage.camera.imageWidth, stage.camera.imageHeight,
                static_cast<unsigned long long>(best.stats.segments), best.stats.shadowMaps.size(),
                configurations[reference].label.c_str(),
                referenceDiagnostics.warningCount() > 0 ? " (the reference warned: not a yardstick)" : "");
    std::printf("| configuration | frame | shadow passes | RMSE | max difference | Pareto |\n"
                "|---|---|---|---|---|---|\n");
    struct Row {
        double seconds = 0.0, shadowSeconds = 0.0, rmse = 0.0, maxDifference = 0.0;
    };
    std::vector<Row> rows;
    auto base = reporter.seconds.find(shadowFrameName(stage, configurations[off]));
    bool forth = true;
    for (const Configuration& configuration : configurations) {
        RenderSettings settings = settingsFor(configuration);
        nudgeLights(stage, forth = !forth);
        RenderResult result = renderer()->render(stage.scene, stage.camera, settings, diagnostics);
        double kept = INFINITY;
        for (int i = 0; i < 3; ++i) kept = std::min(kept, frameCpuSeconds(stage, settings, diagnostics));
        Row row;
        // The reporter keeps times in the benchmarks' unit, milliseconds.
        auto time = reporter.seconds.find(shadowFrameName(stage, configuration));
        if (time != reporter.seconds.end()) row.seconds = 1e-3 * time->second;
        row.shadowSeconds = row.seconds - kept;
        ImageComparison difference = compareImages(result.color, best.color, exactWithin(kOneStep));
        row.rmse = difference.rootMeanSquare;
        row.maxDifference = difference.maxDifference;
        rows.push_back(row);
    }
    for (size_t i = 0; i < rows.size(); ++i) {
        bool dominated = rows[i].seconds <= 0.0 || i == off;
        for (size_t j = 0; j < rows.size() && !dominated; ++j)
            dominated = j != i && j != off && rows[j].seconds > 0.0 && rows[j].seconds <= rows[i].seconds &&
                        rows[j].rmse <= rows[i].rmse &&
                        (rows[j].seconds < rows[i].seconds || rows[j].rmse < rows[i].rmse);
        const std::string frame = rows[i].seconds > 0.0 && base != reporter.seconds.end()
                                      ? fmt::format("{:.2f}x", 1e3 * rows[i].seconds / base->second)
                                      : std::string("not run");
        const std::string shadow =
            i == off || rows[i].seconds <= 0.0
                ? std::string("-")
                : fmt::format("{:.0f} %", 100.0 * std::max(rows[i].shadowSeconds, 0.0) / rows[i].seconds);
        std::printf("| %s | %s | %s | %.5f | %.4f | %s |\n", configurations[i].label.c_str(), frame.c_str(),
                    shadow.c_str(), rows[i].rmse, rows[i].maxDifference, dominated ? "" : "*");
    }
}

// Tessellation, old rule (projectedLength) against new (screenError) at each
// complexity level: triangles one colour pass draws, process CPU seconds of a
// frame relative to projectedLength at low, and the error against the true
// coverage, a 4x4-supersampled render with dense tessellation box-filtered
// to the image size. Sub-pixel strands alias, so every single-sample image
// sits above an error floor, the RMSE of a converged tessellation (screenError
// at 0.001 px); "excess" is what tessellation adds on top.
void printTessellationTable(BenchStage& stage) {
    Diagnostics diagnostics;
    setLightCount(stage, kStageLights);
    constexpr int kSupersampling = 4;
    CameraView supersampled = stage.camera;
    supersampled.imageWidth *= kSupersampling;
    supersampled.imageHeight *= kSupersampling;
    RenderResult dense = renderer()->render(
        stage.scene, supersampled,
        RenderSettings::fromAssignments(Complexity::VeryHigh, {"tessellation=projectedLength",
                                                              fmt::format("pixelsPerSegment={}", kSupersampling),
                                                              "maxSegmentsPerSpan=64"}),
        diagnostics);
    const Image truth = boxDownsample(dense.color, kSupersampling);
    auto errorOf = [&](const RenderResult& result) { return compareImages(result.color, truth, exactWithin(kOneStep)); };
    const ImageComparison floor = errorOf(renderer()->render(
        stage.scene, stage.camera,
        RenderSettings::fromAssignments(Complexity::VeryHigh, {"tessellationTolerance=0.001", "maxSegmentsPerSpan=64"}),
        diagnostics));
    std::printf("\nTessellation, %s (%dx%d): triangles the colour passes drew; process CPU time of a frame relative to "
                "projectedLength at low; error against a %dx%d-supersampled dense render (RMSE floor of a converged "
                "tessellation: %.5f)\n\n",
                stage.path.c_str(), stage.camera.imageWidth, stage.camera.imageHeight, kSupersampling, kSupersampling,
                floor.rootMeanSquare);
    std::printf("| complexity | rule | triangles | frame | RMSE | excess RMSE | max difference |\n"
                "|---|---|---|---|---|---|---|\n");
    double base = 0.0;
    for (const Configuration& level : complexityConfigurations())
        for (const char* rule : {"projectedLength", "screenError"}) {
            RenderSettings settings = RenderSettings::fromAssignments(level.complexity, {std::string("tessellation=") + rule});
            RenderResult result = renderer()->render(stage.scene, stage.camera, settings, diagnostics);
            const double seconds = frameCpuSeconds(stage, settings, diagnostics);
            if (base == 0.0) base = seconds;
            const ImageComparison error = errorOf(result);
            const std::string parameter = std::string(rule) == "screenError"
                                              ? fmt::format("{} px", settings.values().tessellationTolerance)
                                              : fmt::format("{} px a segment", settings.values().pixelsPerSegment);
            std::printf("| %s | %s (%s) | %llu | %.2fx | %.5f | %.5f | %.4f |\n", level.label.c_str(), rule,
                        parameter.c_str(), static_cast<unsigned long long>(result.stats.strandTriangles),
                        seconds / base, error.rootMeanSquare, error.rootMeanSquare - floor.rootMeanSquare,
                        error.maxDifference);
        }
}

// The embedded reader: parsing a large layer, and composition per prim (its
// growth is tested by counting work in testUsdaReader; the seconds are here).
void registerReaderBenchmarks() {
    benchmark::RegisterBenchmark("ParseLayer/5 MB", [](benchmark::State& state) {
        const std::string text = usda::syntheticCurvesLayer(5u * 1024u * 1024u).text;
        for (auto _ : state) benchmark::DoNotOptimize(usda::Stage::openFromString(text, "bench.usda").get());
        state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(text.size()));
    })->Unit(benchmark::kMillisecond);
    for (int prims : {2500, 20000}) {
        benchmark::RegisterBenchmark(fmt::format("ComposeStage/{} prims", prims).c_str(),
                                     [prims](benchmark::State& state) {
                                         const std::string text = usda::siblingPrimsLayer(prims);
                                         for (auto _ : state)
                                             benchmark::DoNotOptimize(
                                                 usda::Stage::openFromString(text, "bench.usda").get());
                                         state.counters["prims/s"] = benchmark::Counter(
                                             double(prims), benchmark::Counter::kIsIterationInvariantRate);
                                     })
            ->Unit(benchmark::kMillisecond);
    }
}

// The dome light's SRBF-convolution tables: what a material's first frame
// waits for when the disk cache has no table for it (README, hdHair/shading).
void registerSrbfTableBenchmarks() {
    benchmark::RegisterBenchmark("SrbfTables/Build/marschner", [](benchmark::State& state) {
        for (auto _ : state) benchmark::DoNotOptimize(buildSrbfMarschnerTable(MarschnerParameters()).texels.data());
    })->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark("SrbfTables/Build/marschner-lobes", [](benchmark::State& state) {
        for (auto _ : state)
            benchmark::DoNotOptimize(buildSrbfMarschnerLobeTable(MarschnerParameters()).texels.data());
    })->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark("SrbfTables/Build/kajiya-kay", [](benchmark::State& state) {
        for (auto _ : state)
            benchmark::DoNotOptimize(buildSrbfKajiyaKayTable(KajiyaKayParameters().shininess).texels.data());
    })->Unit(benchmark::kMillisecond);
}

// A dome texture's read and fit (hdHair/environment/SrbfFit.h), on a
// 1024 × 512 sky written once to the temporary folder.
void registerEnvironmentBenchmarks() {
    benchmark::RegisterBenchmark("SrbfFit/1024x512", [](benchmark::State& state) {
        const glm::vec3 sun = glm::normalize(glm::vec3(0.4f, 0.7f, -0.6f));
        Image sky(1024, 512, 4, 1.0f);
        for (int y = 0; y < sky.height; ++y) {
            for (int x = 0; x < sky.width; ++x) {
                const glm::vec3 d = latlongDirection((float(x) + 0.5f) / 1024.0f, (float(y) + 0.5f) / 512.0f);
                const glm::vec3 radiance = glm::mix(glm::vec3(0.9f, 0.8f, 0.6f), glm::vec3(0.2f, 0.4f, 0.9f),
                                                    std::max(d.y, 0.0f)) +
                                           50.0f * std::pow(std::max(glm::dot(d, sun), 0.0f), 2000.0f);
                for (int c = 0; c < 3; ++c) sky.at(x, y, c) = radiance[c];
            }
        }
        const std::string path =
            (std::filesystem::temp_directory_path() / ("hdhair-bench-sky-" + std::to_string(::getpid()) + ".exr"))
                .string();
        writeImage(sky, path);
        const DomeFitSettings settings;
        for (auto _ : state) {
            const LatlongTextureRead read = readLatlongTexture(path, settings.gridWidth, settings.gridHeight);
            benchmark::DoNotOptimize(fitSrbfs(read.grid, settings.srbf).srbfs.data());
        }
        std::filesystem::remove(path);
    })->Unit(benchmark::kMillisecond);
}

// What the command line asks for.
struct BenchOptions {
    std::vector<std::string> stagePaths;
    int imageWidth = 0;
    std::string table = "all";
    bool accuracyRun = false, quick = false, cyclesRun = false;
    int repetitions = 3;
    accuracy::CyclesComparison cycles;
    std::string out = "accuracy", report, domeTexture = HDHAIR_SOURCE_DIR "/examples/dome_sky.exr";
    std::vector<std::string> approximations;
    std::string command;                 // as typed, for the accuracy report
    std::vector<std::string> benchmark;  // what CLI11 does not know, for Google Benchmark
};

// The --accuracy and --cycles options.
void addAccuracyOptions(CLI::App& app, BenchOptions& options) {
    auto* accuracyFlag = app.add_flag("--accuracy", options.accuracyRun,
                                      "The error-versus-time matrix of every approximation and preset (AccuracyBench.h)");
    app.add_flag("--quick", options.quick, "--accuracy: the CI run (short ladders, one repetition, 64 pixels wide)")
        ->needs(accuracyFlag);
    app.add_option("--out", options.out, "--accuracy, --report: the folder for accuracy.{json,csv,md}")
        ->capture_default_str();
    app.add_option("--report", options.report, "Write an earlier run's accuracy.json report again (front, tables, checks)");
    auto* cyclesFlag =
        app.add_flag("--cycles", options.cyclesRun, "--accuracy: against Blender's Cycles too")->needs(accuracyFlag);
    app.add_option("--approximations", options.approximations,
                   "--accuracy: only these approximations of the matrix, by name (\"preset\" for the quality presets; "
                   "repeatable, or comma-separated)")
        ->delimiter(',')
        ->needs(accuracyFlag);
    app.add_option("--cyclesSamples", options.cycles.samples, "--cycles: Cycles' samples per pixel")
        ->check(CLI::Range(1, 1 << 20))
        ->needs(cyclesFlag)
        ->capture_default_str();
    app.add_option("--cyclesBlock", options.cycles.block, "--cycles: the side of the blocks errors are measured over, pixels")
        ->check(CLI::Range(1, 1024))
        ->needs(cyclesFlag)
        ->capture_default_str();
    app.add_option("--blender", options.cycles.blender, "--cycles: the Blender executable")
        ->needs(cyclesFlag)
        ->capture_default_str();
}

// Parses the command line into `options`; an exit status when it should end
// the program (help, or 2 for a command line that does not parse).
std::optional<int> parseOptions(int argc, char** argv, BenchOptions& options) {
    for (int i = 0; i < argc; ++i) options.command += (i ? " " : "") + std::string(argv[i]);
    CLI::App app{"What accuracy costs in time: Google Benchmark tables, the accuracy matrix (--accuracy) and the "
                 "dome lighting table (--table dome).",
                 "hdhair-bench"};
    app.add_option("--stage", options.stagePaths, "A stage to measure (repeatable; default examples/dense_clump.usda)");
    app.add_option("--imageWidth", options.imageWidth,
                   "Image width in pixels (default 512; 128 with --accuracy or --table dome, 64 with --quick)")
        ->check(CLI::Range(1, 16384));
    app.add_option("--table", options.table, "Which Google Benchmark tables, or the dome table")
        ->check(CLI::IsMember({"all", "complexity", "transparency", "shading", "shadows", "tessellation", "dome"}))
        ->capture_default_str();
    app.add_option("--repetitions", options.repetitions, "Frames timed per configuration (--accuracy, --table dome)")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    app.add_option("--domeTexture", options.domeTexture, "--table dome: the latlong sky")->capture_default_str();
    addAccuracyOptions(app, options);
    app.footer("Other arguments (--benchmark_filter=REGEX, --benchmark_repetitions=N, ...) go to Google Benchmark.");
    // Google Benchmark reads the arguments CLI11 does not know.
    app.allow_extras();
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& help) {
        return app.exit(help);
    } catch (const CLI::ParseError& error) {
        std::fprintf(stderr, "hdhair-bench: error: %s\n", error.what());
        return 2;
    }
    options.benchmark = app.remaining();
    if (options.quick) options.repetitions = 1;
    // Accuracy frames are many (about 50 configurations a stage, the
    // reference 16 samples a pixel): small images keep the matrix to minutes.
    // So are dome frames: the reference is a thousand lights, each with a map.
    if (options.imageWidth == 0)
        options.imageWidth = options.accuracyRun || options.table == "dome" ? (options.quick ? 64 : 128) : 512;
    if (options.stagePaths.empty()) options.stagePaths.push_back(HDHAIR_SOURCE_DIR "/examples/dense_clump.usda");
    return std::nullopt;
}

// Hands Google Benchmark its arguments; 2 when some are neither its nor ours.
int initializeBenchmark(BenchOptions& options) {
    std::string programName = "hdhair-bench";
    std::vector<char*> arguments{programName.data()};
    for (std::string& extra : options.benchmark) arguments.push_back(extra.data());
    int count = int(arguments.size());
    benchmark::Initialize(&count, arguments.data());
    // What neither CLI11 nor Google Benchmark knows is a typo, not a default.
    if (count <= 1) return 0;
    std::string unknown;
    for (int i = 1; i < count; ++i) unknown += (i > 1 ? " " : "") + std::string(arguments[i]);
    std::fprintf(stderr, "hdhair-bench: error: unknown arguments: %s (--help lists them)\n", unknown.c_str());
    return 2;
}

// --report FILE: the report of an earlier --accuracy run marked and written
// again (after a change to the report's tables or front).
int rewriteReport(const BenchOptions& options) {
    try {
        std::string text;
        if (std::string why = readRegularFile(options.report, text); !why.empty()) throw std::runtime_error(why);
        nlohmann::json earlier = nlohmann::json::parse(text);
        accuracy::markParetoFront(earlier);
        std::vector<std::string> notes;
        earlier["checks"] = accuracy::checkAccuracyReport(earlier, &notes);
        earlier["checkNotes"] = notes;
        accuracy::writeAccuracyReport(earlier, options.out);
        std::printf("%s", accuracy::accuracyMarkdown(earlier).c_str());
        return 0;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "hdhair-bench: error: %s: %s\n", options.report.c_str(), error.what());
        return 1;
    }
}

// A stage read, prepared and framed for the tables.
std::unique_ptr<BenchStage> loadStage(const std::string& path, int imageWidth) {
    auto stage = std::make_unique<BenchStage>();
    stage->path = path;
    stage->name = std::filesystem::path(path).stem().string();
    Diagnostics diagnostics;
    usda::readSceneFile(path, -INFINITY, stage->scene, diagnostics);
    SceneBounds bounds = renderer()->prepare(stage->scene, RenderSettings(), diagnostics);
    auto camera = stage->scene.cameras().begin();
    stage->camera = camera != stage->scene.cameras().end()
                        ? cameraViewFromPrim(*camera->second.prim, imageWidth)
                        : frameBounds(bounds.min, bounds.max, stage->scene.info().upAxis, imageWidth,
                                      FramingStyle::FitAll);
    for (const auto& [lightPath, entry] : stage->scene.lights()) stage->stageLights.push_back(*entry.prim);
    for (const auto& [curvesPath, entry] : stage->scene.curves()) {
        stage->prepared.push_back(prepareCurves(*entry.prim, diagnostics));
        stage->sortHashes.push_back(segmentSortHashes(stage->prepared.back()));
    }
    for (size_t i = 0; i < stage->prepared.size(); ++i) {
        const PreparedCurves& curves = stage->prepared[i];
        stage->sortSpans.push_back(SortSpan{curves.controlPoints.data(), curves.segmentFirstControl.data(),
                                            stage->sortHashes[i].data(), curves.segmentCount(), stage->segments});
        stage->segments += curves.segmentCount();
    }
    return stage;
}

// --table dome (DomeBench.h).
int runDomeTable(const std::vector<std::unique_ptr<BenchStage>>& stages, const BenchOptions& options) {
    std::vector<DomeBenchStage> domeStages;
    for (const auto& stage : stages) domeStages.push_back({stage->name, stage->path, &stage->scene, stage->camera});
    printDomeTables(*renderer(), domeStages, {options.domeTexture, options.repetitions});
    return 0;
}

// --accuracy (AccuracyBench.h): the matrix, its report and its checks.
int runAccuracy(const std::vector<std::unique_ptr<BenchStage>>& stages, BenchOptions& options) {
    std::vector<accuracy::AccuracyStage> accuracyStages;
    for (const auto& stage : stages) accuracyStages.push_back({stage->name, stage->path, &stage->scene, stage->camera});
    accuracy::AccuracyRun run{options.quick, options.repetitions, options.command, std::nullopt, options.approximations};
    if (options.cyclesRun) {
        options.cycles.imagesFolder = options.out;
        std::filesystem::create_directories(options.out);
        run.cycles = options.cycles;
    }
    nlohmann::json results = accuracy::runAccuracyBench(*renderer(), accuracyStages, run);
    accuracy::markParetoFront(results);
    std::vector<std::string> notes;
    // The checks read the whole matrix (every ladder, the presets): a part
    // of it (--approximations) is reported, not checked.
    const bool whole = options.approximations.empty();
    const std::vector<std::string> problems =
        whole ? accuracy::checkAccuracyReport(results, &notes) : std::vector<std::string>();
    if (!whole) notes.push_back("a part of the matrix (--approximations): not checked");
    results["checks"] = problems;
    results["checkNotes"] = notes;
    accuracy::writeAccuracyReport(results, options.out);
    std::printf("%s", accuracy::accuracyMarkdown(results).c_str());
    for (const std::string& note : notes) std::printf("hdhair-bench: note: %s\n", note.c_str());
    for (const std::string& problem : problems) std::printf("hdhair-bench: check failed: %s\n", problem.c_str());
    std::printf("hdhair-bench: accuracy matrix in %.0f s, %zu checks failed; wrote %s/accuracy.{json,csv,md}\n",
                results["seconds"].get<double>(), problems.size(), options.out.c_str());
    // The checks' allowances are set for the matrix's own shading; against
    // Cycles (every frame Marschner) they are reported only.
    return options.quick && !options.cyclesRun && !problems.empty() ? 1 : 0;
}

// Which Google Benchmark tables run (--table), and their configurations.
struct Tables {
    explicit Tables(const std::string& table)
        : complexity(table == "all" || table == "complexity"), transparency(table == "all" || table == "transparency"),
          shading(table == "all" || table == "shading"), shadow(table == "all" || table == "shadows"),
          tessellation(table == "all" || table == "tessellation") {}
    bool complexity, transparency, shading, shadow, tessellation;
    std::vector<Configuration> complexities = complexityConfigurations();
    std::vector<Configuration> transparencies = transparencyConfigurations();
    std::vector<Configuration> shadows = shadowConfigurations();
    std::vector<ShadingConfiguration> shadings = shadingConfigurations();
};

// A stage's curve preparation and bin sort, timed alone.
void registerStageBenchmarks(BenchStage* stage) {
    benchmark::RegisterBenchmark(("PrepareCurves/" + stage->name).c_str(), [stage](benchmark::State& state) {
        Diagnostics diagnostics;
        for (auto _ : state)
            for (const auto& [path, entry] : stage->scene.curves())
                benchmark::DoNotOptimize(prepareCurves(*entry.prim, diagnostics).controlPoints.data());
    })->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("BinSort/" + stage->name).c_str(), [stage](benchmark::State& state) {
        const glm::dvec3 position = stage->camera.position(), direction = stage->camera.forward();
        std::vector<uint32_t> order;
        for (auto _ : state) {
            binSortSegments(stage->sortSpans, position, direction, 256, order);
            benchmark::DoNotOptimize(order.data());
        }
        state.counters["segments/s"] =
            benchmark::Counter(double(stage->segments), benchmark::Counter::kIsIterationInvariantRate);
    })->Unit(benchmark::kMillisecond);
}

// Every benchmark the tables asked for read.
void registerTableBenchmarks(const std::vector<std::unique_ptr<BenchStage>>& stages, const Tables& tables) {
    registerReaderBenchmarks();
    registerSrbfTableBenchmarks();
    registerEnvironmentBenchmarks();
    for (const auto& stagePointer : stages) {
        BenchStage* stage = stagePointer.get();
        registerStageBenchmarks(stage);
        std::vector<Configuration> frames;
        if (tables.complexity) frames.insert(frames.end(), tables.complexities.begin(), tables.complexities.end());
        if (tables.transparency)
            frames.insert(frames.end(), tables.transparencies.begin(), tables.transparencies.end());
        for (const Configuration& configuration : frames) registerFrame(stage, configuration, kStageLights);
    }
    for (const auto& stage : stages) {
        if (tables.shading)
            for (const ShadingConfiguration& shading : tables.shadings)
                registerFrame(stage.get(), shading.configuration, shading.lights);
        if (tables.shadow)
            for (const Configuration& configuration : tables.shadows) registerShadowFrame(stage.get(), configuration);
    }
}

// The complexity, tessellation and transparency tables of a stage.
void printFrameTables(BenchStage& stage, const Tables& tables, const RecordingReporter& reporter) {
    setLightCount(stage, kStageLights);
    if (tables.complexity) printTable(stage, tables.complexities, 3, 0, reporter, "Complexity");
    if (tables.tessellation) printTessellationTable(stage);
    if (!tables.transparency) return;
    printTable(stage, tables.transparencies, tables.transparencies.size() - 1, 0, reporter, "Transparency");
    auto sort = reporter.seconds.find("BinSort/" + stage.name);
    auto sorted = reporter.seconds.find(frameName(stage, tables.transparencies[5]));  // binSorted 256
    if (sort != reporter.seconds.end() && sorted != reporter.seconds.end())
        std::printf("\nThe CPU bin sort (256 bins) is %.1f%% of a binSorted frame.\n",
                    100.0 * sort->second / sorted->second);
}

// Each shading model's time with 1 to 16 lights, relative to flat with one.
void printShadingTable(const BenchStage& stage, const Tables& tables, const RecordingReporter& reporter) {
    std::printf("\nShading, %s: time relative to flat with 1 light (same run)\n\n| model | 1 light | 4 lights | "
                "8 lights | 16 lights |\n|---|---|---|---|---|\n",
                stage.path.c_str());
    auto base = reporter.seconds.find(frameName(stage, tables.shadings[0].configuration));
    for (size_t i = 0; i < tables.shadings.size(); i += 4) {
        std::string row = "| " + tables.shadings[i].model + " |";
        for (size_t j = i; j < i + 4; ++j) {
            auto time = reporter.seconds.find(frameName(stage, tables.shadings[j].configuration));
            row += (time != reporter.seconds.end() && base != reporter.seconds.end())
                       ? fmt::format(" {:.2f}x |", time->second / base->second)
                       : " not run |";
        }
        std::printf("%s\n", row.c_str());
    }
}

// The images of the two Marschner paths against analytic, with the stage's own lights.
void printMarschnerImageTable(BenchStage& stage) {
    setLightCount(stage, kStageLights);
    Diagnostics diagnostics;
    auto marschnerImage = [&](MarschnerAzimuthal azimuthal) {
        RenderSettings settings;
        settings.setValue(&SettingValues::shadingModel, ShadingModel::Marschner);
        settings.setValue(&SettingValues::marschnerAzimuthal, azimuthal);
        return renderer()->render(stage.scene, stage.camera, settings, diagnostics).color;
    };
    Image analytic = marschnerImage(MarschnerAzimuthal::Analytic);
    double peak = 0.0;
    for (float value : analytic.pixels) peak = std::max(peak, double(value));
    std::printf("\nMarschner images, %s: against analytic (GPU, stage lights; brightest channel %.3f)\n\n"
                "| marschner:azimuthal | RMSE | max difference | pixels over 1/255 |\n|---|---|---|---|\n",
                stage.path.c_str(), peak);
    for (MarschnerAzimuthal azimuthal : {MarschnerAzimuthal::Tables, MarschnerAzimuthal::Auto}) {
        // exactWithin: every covered pixel more than a step apart is an outlier.
        ImageComparison difference = compareImages(marschnerImage(azimuthal), analytic, exactWithin(kOneStep));
        std::printf("| %s | %.5f | %.4f | %.2f%% |\n", toString(azimuthal), difference.rootMeanSquare,
                    difference.maxDifference,
                    100.0 * double(difference.outliers) / double(std::max<size_t>(difference.coveredPixels, 1)));
    }
}

// Tabled Marschner against analytic on the CPU, over directions a frame would see.
void printMarschnerTableErrors() {
    MarschnerParameters parameters;
    parameters.sigmaA = marschnerSigmaAFromMelanin(0.3f, 0.0f);
    std::printf("\nMarschner, tabled against analytic (radiance over 20,000 random directions):\n\n"
                "| table | precision | max | RMS | max / peak |\n|---|---|---|---|---|\n");
    for (const MarschnerTableError& error : measureMarschnerTableErrors(parameters, {32, 64, 128}))
        std::printf("| %dx%d | %s | %.4f | %.6f | %.2f%% |\n", error.width, error.height,
                    error.precision == MarschnerTablePrecision::Half ? "half" : "float", error.maxAbsolute,
                    error.rms, 100.0 * error.maxAbsolute / error.peak);
}

// The Google Benchmark tables (--table): registered, run, printed.
int runTables(const std::vector<std::unique_ptr<BenchStage>>& stages, const BenchOptions& options) {
    const Tables tables(options.table);
    registerTableBenchmarks(stages, tables);
    RecordingReporter reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);
    for (const auto& stage : stages) printFrameTables(*stage, tables, reporter);
    for (const auto& stage : stages) {
        if (!tables.shading) break;
        printShadingTable(*stage, tables, reporter);
    }
    for (const auto& stage : stages) {
        if (!tables.shading) break;
        printMarschnerImageTable(*stage);
    }
    for (const auto& stage : stages)
        if (tables.shadow) printShadowTable(*stage, tables.shadows, reporter);
    if (tables.shading) printMarschnerTableErrors();
    benchmark::Shutdown();
    return 0;
}

// Runs `job` with the renderer made, turning an error into one line and exit 1.
template <typename Job>
int withRenderer(Job&& job) {
    try {
        renderer() = std::make_unique<Renderer>(gl::defaultGlBackend());
        const int status = job();
        renderer().reset();
        return status;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "hdhair-bench: error: %s\n", error.what());
        return 1;
    }
}

}  // namespace

int main(int argc, char** argv) {
    BenchOptions options;
    if (std::optional<int> status = parseOptions(argc, argv, options)) return *status;
    if (!options.report.empty()) return rewriteReport(options);
    if (int status = initializeBenchmark(options); status != 0) return status;
    return withRenderer([&] {
        std::vector<std::unique_ptr<BenchStage>> stages;
        for (const std::string& path : options.stagePaths) stages.push_back(loadStage(path, options.imageWidth));
        std::printf("hdhair-bench: %s on %s\n", renderer()->glDescription().c_str(), renderer()->glDevice().c_str());
        if (options.table == "dome") return runDomeTable(stages, options);
        if (options.accuracyRun) return runAccuracy(stages, options);
        return runTables(stages, options);
    });
}
