// hdhair-bench: what accuracy costs in time, measured with Google Benchmark.
//
// Benchmarks (on examples/dense_clump.usda unless --stage is given):
//   PrepareCurves          CPU curve preparation (resolution + change of basis)
//   RenderFrame/<level>    a whole frame at each --complexity level
// After the runs it prints a table for the frame benchmarks: time relative to
// the "low" level measured in the same run (these machines are shared and
// noisy, so ratios mean more than milliseconds), and the image error of each
// level against the finest one (RMSE and largest difference, pre-multiplied
// RGBA), so tessellation density can be chosen by what it buys.
//
//   hdhair-bench [--stage FILE] [--imageWidth N] [Google Benchmark flags]

#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/curves/PreparedCurves.h"
#include "hdHair/image/ImageComparison.h"
#include "hdHair/render/CameraView.h"
#include "hdHair/render/Renderer.h"
#include "hdHair/scene/Scene.h"
#include "hdHair/usda/SceneReader.h"

namespace {

using namespace hdhair;

struct BenchContext {
    std::string stagePath = HDHAIR_SOURCE_DIR "/examples/dense_clump.usda";
    int imageWidth = 512;
    Scene scene;
    std::unique_ptr<Renderer> renderer;
    CameraView camera;
};

BenchContext& context() {
    static BenchContext instance;
    return instance;
}

const Complexity kLevels[] = {Complexity::Low, Complexity::Medium, Complexity::High, Complexity::VeryHigh};

RenderSettings settingsFor(Complexity level) {
    RenderSettings settings;
    settings.setComplexity(level);
    return settings;
}

void PrepareCurves(benchmark::State& state) {
    BenchContext& c = context();
    Diagnostics diagnostics;
    size_t segments = 0;
    for (auto _ : state) {
        for (const auto& [path, entry] : c.scene.curves()) {
            PreparedCurves prepared = prepareCurves(*entry.prim, diagnostics);
            segments = prepared.segmentCount();
            benchmark::DoNotOptimize(prepared.controlPoints.data());
        }
    }
    state.counters["segments/s"] =
        benchmark::Counter(double(segments), benchmark::Counter::kIsIterationInvariantRate);
}

void RenderFrame(benchmark::State& state) {
    BenchContext& c = context();
    Complexity level = kLevels[state.range(0)];
    RenderSettings settings = settingsFor(level);
    Diagnostics diagnostics;
    for (auto _ : state) {
        RenderResult result = c.renderer->render(c.scene, c.camera, settings, diagnostics);
        benchmark::DoNotOptimize(result.color.pixels.data());
    }
    state.SetLabel(toString(level));
}

// Keeps each run's time so the summary can relate them.
class RecordingReporter : public benchmark::ConsoleReporter {
public:
    void ReportRuns(const std::vector<Run>& runs) override {
        for (const Run& run : runs)
            if (run.run_type == Run::RT_Iteration && !run.report_label.empty())
                seconds[run.report_label] = run.GetAdjustedRealTime();
        ConsoleReporter::ReportRuns(runs);
    }
    std::map<std::string, double> seconds;  // by label: the complexity level
};

}  // namespace

int main(int argc, char** argv) {
    BenchContext& c = context();
    std::vector<char*> benchmarkArguments;
    for (int i = 0; i < argc; ++i) {
        if (i + 1 < argc && std::strcmp(argv[i], "--stage") == 0) c.stagePath = argv[++i];
        else if (i + 1 < argc && std::strcmp(argv[i], "--imageWidth") == 0) c.imageWidth = std::atoi(argv[++i]);
        else benchmarkArguments.push_back(argv[i]);
    }
    int benchmarkArgc = int(benchmarkArguments.size());
    benchmark::Initialize(&benchmarkArgc, benchmarkArguments.data());

    try {
        Diagnostics diagnostics;
        usda::readSceneFile(c.stagePath, -INFINITY, c.scene, diagnostics);
        c.renderer = std::make_unique<Renderer>(gl::defaultGlBackend());
        SceneBounds bounds = c.renderer->prepare(c.scene, diagnostics);
        auto camera = c.scene.cameras().begin();
        c.camera = camera != c.scene.cameras().end()
                       ? cameraViewFromPrim(*camera->second.prim, c.imageWidth)
                       : frameBounds(bounds.min, bounds.max, c.scene.info().upAxis, c.imageWidth, FramingStyle::FitAll);
        std::printf("hdhair-bench: %s at %dx%d on %s\n", c.stagePath.c_str(), c.camera.imageWidth,
                    c.camera.imageHeight, c.renderer->glDescription().c_str());
    } catch (const std::exception& error) {
        std::fprintf(stderr, "hdhair-bench: error: %s\n", error.what());
        return 1;
    }

    benchmark::RegisterBenchmark("PrepareCurves", PrepareCurves)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark("RenderFrame", RenderFrame)
        ->DenseRange(0, 3)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
    RecordingReporter reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);

    // Image error of each level against the finest, rendered once each.
    Diagnostics diagnostics;
    RenderResult finest = c.renderer->render(c.scene, c.camera, settingsFor(Complexity::VeryHigh), diagnostics);
    auto lowTime = reporter.seconds.find(toString(Complexity::Low));
    std::printf("\n| complexity | segments/span | time vs low | RMSE vs veryhigh | max difference |\n");
    std::printf("|---|---|---|---|---|\n");
    for (int i = 0; i < 4; ++i) {
        RenderSettings settings = settingsFor(kLevels[i]);
        RenderResult result = c.renderer->render(c.scene, c.camera, settings, diagnostics);
        ImageDifference difference = compareImages(result.color, finest.color, 1.0 / 255.0);
        auto time = reporter.seconds.find(toString(kLevels[i]));
        std::string ratio = (time != reporter.seconds.end() && lowTime != reporter.seconds.end())
                                ? fmt::format("{:.2f}x", time->second / lowTime->second)
                                : "not run";
        std::printf("| %s | at most %d | %s | %.5f | %.4f |\n", toString(kLevels[i]),
                    settings.getInt("maxSegmentsPerSpan"), ratio.c_str(), difference.rootMeanSquare,
                    difference.maxDifference);
    }
    benchmark::Shutdown();
    return 0;
}
