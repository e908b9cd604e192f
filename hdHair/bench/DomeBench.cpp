#include "hdHair/bench/DomeBench.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/image/ImageComparison.h"
#include "hdHair/render/Renderer.h"
#include "hdHair/scene/Scene.h"
#include "hdHair/bench/BenchLights.h"

namespace hdhair {

namespace {

struct DomeRow {
    std::string label;
    std::vector<std::string> settings;  // NAME=VALUE, over the bench's common settings
    bool shadowed = true;               // compared with the shadowed reference
};

struct MeasuredRow {
    double medianMs = 0.0;
    float fitError = 0.0f;
    Image image;
};

std::vector<DomeRow> domeRows() {
    std::vector<DomeRow> rows = {{"ambient (flat, the time base)", {"domeLighting=ambient"}, true}};
    for (int lobes : {10, 20, 30, 40, 60})
        rows.push_back({fmt::format("{} SRBFs, 4 maps, taps", lobes),
                        {fmt::format("domeLights={}", lobes), "domeShadowFilter=taps"},
                        true});
    for (int maps : {0, 1, 8, 30})
        rows.push_back({fmt::format("30 SRBFs, {} map{}{}, taps", maps, maps == 1 ? "" : "s",
                                    maps == 30 ? " (one a lobe)" : ""),
                        {"domeLights=30", fmt::format("domeShadowLights={}", maps), "domeShadowFilter=taps"},
                        true});
    // The paper's convolution optical depth map (the default) instead of nine taps.
    for (int maps : {4, 30})
        rows.push_back({fmt::format("30 SRBFs, {} maps, mip chain", maps),
                        {"domeLights=30", fmt::format("domeShadowLights={}", maps), "domeShadowFilter=mipmap"},
                        true});
    for (int lobes : {10, 20, 30, 40, 60})
        rows.push_back({fmt::format("{} SRBFs, unshadowed", lobes),
                        {fmt::format("domeLights={}", lobes), "shadowMode=off"},
                        false});
    return rows;
}

// The stage lit by the dome alone.
void lightWithDome(Scene& scene, const std::string& texture) {
    std::vector<std::string> paths;
    for (const auto& [path, entry] : scene.lights()) paths.push_back(path);
    for (const std::string& path : paths) scene.remove(path);
    LightPrim dome;
    dome.path = "/DomeBench/dome";
    dome.type = LightType::Dome;
    dome.textureFile = texture;
    scene.setLight(dome);
}

RenderSettings rowSettings(const DomeBenchOptions& options, const std::vector<std::string>& assignments) {
    RenderSettings settings = RenderSettings::fromAssignments(Complexity::Low, assignments);
    settings.set("shadowMapResolution", std::to_string(options.mapResolution));
    // Room for every reference light's map (3 layers: 16 bytes a texel), and
    // more lights a pass: the reference has a thousand of them.
    const double referenceMB = double(options.referenceLights) * options.mapResolution * options.mapResolution * 16.0 /
                               (1024.0 * 1024.0);
    settings.set("shadowMemoryMB", std::to_string(std::max(1024, int(referenceMB) + 64)));
    settings.set("lightsPerPass", "16");
    return settings;
}

// `repetitions` timed frames; an SRBF row first renders one untimed frame,
// which fits the dome and builds the tables (both cached after it).
MeasuredRow measure(Renderer& renderer, Scene& scene, const CameraView& camera, const RenderSettings& settings,
                    int repetitions, const std::string& what) {
    Diagnostics diagnostics;
    std::fprintf(stderr, "hdhair-bench: dome: %s ...\n", what.c_str());
    MeasuredRow row;
    if (settings.values().domeLighting == DomeLightingMode::Srbf) {
        RenderResult first = renderer.render(scene, camera, settings, diagnostics);
        for (const PlannedDome& dome : first.plan.recipe().lighting.domes) row.fitError = dome.fitError;
    }
    std::vector<double> milliseconds;
    bool forth = true;
    for (int i = 0; i < repetitions; ++i) {
        turnLightsAboutY(scene, (forth = !forth) ? 1e-6 : -1e-6);
        RenderResult timed = renderer.render(scene, camera, settings, diagnostics);
        milliseconds.push_back(timed.stats.totalMilliseconds);
        if (i + 1 == repetitions) row.image = std::move(timed.color);
    }
    std::sort(milliseconds.begin(), milliseconds.end());
    const size_t n = milliseconds.size();
    row.medianMs = n % 2 ? milliseconds[n / 2] : 0.5 * (milliseconds[n / 2 - 1] + milliseconds[n / 2]);
    for (const Diagnostic& warning : diagnostics.warnings())
        std::fprintf(stderr, "hdhair-bench: dome: warning: %s: %s\n", warning.where.c_str(), warning.message.c_str());
    return row;
}

}  // namespace

void printDomeTables(Renderer& renderer, const std::vector<DomeBenchStage>& stages, const DomeBenchOptions& options) {
    const std::vector<DomeRow> rows = domeRows();
    for (const DomeBenchStage& stage : stages) {
        lightWithDome(*stage.scene, options.texture);
        std::vector<MeasuredRow> measured;
        for (const DomeRow& row : rows)
            measured.push_back(measure(renderer, *stage.scene, stage.camera, rowSettings(options, row.settings),
                                       options.repetitions, row.label));
        // The references last: their thousand maps grow the renderer's map
        // storage, which the rows' mip chains (generated over the whole
        // array) would then pay for.
        const std::string sampledLights = fmt::format("domeSampledLights={}", options.referenceLights);
        const MeasuredRow shadowedReference =
            measure(renderer, *stage.scene, stage.camera,
                    rowSettings(options, {"domeLighting=sampled", sampledLights}), 1, "reference, shadowed");
        const MeasuredRow unshadowedReference =
            measure(renderer, *stage.scene, stage.camera,
                    rowSettings(options, {"domeLighting=sampled", sampledLights, "shadowMode=off"}), 1,
                    "reference, unshadowed");
        const double base = measured.front().medianMs;
        std::printf("\nDome lighting, %s (%dx%d) under %s: time relative to ambient (median of %d frames, each "
                    "rebuilding its maps; %d-texel maps), error against the reference (%d sampled lights, one frame)\n\n"
                    "| dome lighting | fit error | time | relative RMSE | largest / peak |\n|---|---|---|---|---|\n",
                    stage.path.c_str(), stage.camera.imageWidth, stage.camera.imageHeight, options.texture.c_str(),
                    options.repetitions, options.mapResolution, options.referenceLights);
        for (size_t i = 0; i < rows.size(); ++i) {
            const RelativeColorError error = relativeColorError(
                measured[i].image, (rows[i].shadowed ? shadowedReference : unshadowedReference).image);
            const std::string fitError = i == 0 ? "-" : fmt::format("{:.3f}", measured[i].fitError);
            std::printf("| %s | %s | %.2fx | %.3f | %.3f |\n", rows[i].label.c_str(), fitError.c_str(),
                        measured[i].medianMs / base, error.rootMeanSquare, error.largest);
        }
        std::printf("| reference, shadowed | - | %.2fx | 0 | 0 |\n| reference, unshadowed | - | %.2fx | 0 | 0 |\n",
                    shadowedReference.medianMs / base, unshadowedReference.medianMs / base);
        std::fflush(stdout);
    }
}

}  // namespace hdhair
