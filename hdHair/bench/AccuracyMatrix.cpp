#include "hdHair/bench/AccuracyMatrix.h"

#include <fmt/format.h>

#include "hdHair/plan/QualityPresets.h"
#include "hdHair/plan/RenderSettings.h"

namespace hdhair::accuracy {

const char* toString(ErrorTrend trend) { return trend == ErrorTrend::Falls ? "falls" : "flat"; }

namespace {

// A ladder of one setting: `values` cheapest first.
std::vector<Step> ladder(const std::string& name, const std::vector<std::string>& values, const char* unit) {
    const std::string defaultValue = RenderSettings().getToken(name);
    std::vector<Step> steps;
    for (const std::string& value : values)
        steps.push_back({value + unit, {name + "=" + value}, value == defaultValue});
    return steps;
}

// Keeps the first, the default and the last steps (the quick matrix).
std::vector<Step> ends(const std::vector<Step>& steps) {
    std::vector<Step> kept;
    for (size_t i = 0; i < steps.size(); ++i)
        if (i == 0 || i + 1 == steps.size() || steps[i].isDefault) kept.push_back(steps[i]);
    return kept;
}

// How strands are composited and in what order.
void addCompositingApproximations(std::vector<Approximation>& matrix) {
    matrix.push_back({"sortBins", "depth bins of binSorted transparency: order errors within a bin against sort cost",
                      {},
                      ladder("sortBins", {"1", "16", "64", "256", "1024"}, " bins"),
                      ErrorTrend::Falls});
    matrix.push_back({"transparency",
                      "how strands are composited: opaque (no coverage), unsorted, binSorted, exact per-pixel lists",
                      {},
                      ladder("transparency", {"opaque", "unsorted", "binSorted", "exact"}, ""),
                      ErrorTrend::Falls});
}

Approximation tessellationApproximation() {
    // Tolerance and the cap on segments a span move together, as complexity
    // moves them: a tolerance under the cap's reach changes nothing.
    std::vector<Step> tessellation;
    const std::pair<const char*, const char*> levels[] = {
        {"0.48", "4"}, {"0.24", "8"}, {"0.12", "8"}, {"0.06", "16"}, {"0.03", "32"}, {"0.015", "64"}};
    for (const auto& [tolerance, segments] : levels)
        tessellation.push_back({fmt::format("{} px, {} a span", tolerance, segments),
                                {std::string("tessellationTolerance=") + tolerance,
                                 std::string("maxSegmentsPerSpan=") + segments},
                                std::string(tolerance) == "0.12"});
    return {"tessellation",
            "screen-space tessellation tolerance (and the most segments a span may get): polyline error "
            "against segments drawn",
            {},
            tessellation,
            ErrorTrend::Falls};
}

// The deep opacity maps: their layers, resolution and tessellation.
void addShadowApproximations(std::vector<Approximation>& matrix) {
    std::vector<Step> layers = {{"off", {"shadowMode=off"}, false}};
    for (Step& step : ladder("shadowLayers", {"1", "3", "7", "15"}, " layers")) layers.push_back(step);
    matrix.push_back({"shadowLayers",
                      "deep opacity layers behind the nearest hair (off: no self-shadowing): opacity resolution "
                      "along the light against shadow passes",
                      {},
                      layers,
                      ErrorTrend::Falls});
    // From the coarse end up to the default only: with 3 layers, finer maps
    // than 512 do not lower the error (README, shadow benchmark), so the
    // ladder's trend would be noise above it. 2048 is measured but the check
    // stops at the default.
    matrix.push_back({"shadowMapResolution",
                      "texels across each light's deep opacity map: shadow detail across the light against map "
                      "memory and passes",
                      {},
                      ladder("shadowMapResolution", {"128", "256", "512", "2048"}, " texels"),
                      ErrorTrend::Falls, false});
    matrix.push_back({"shadowTessellationTolerance",
                      "the light views' tessellation tolerance in texels: the maps' polylines against the "
                      "segments the light views draw",
                      {},
                      ladder("shadowTessellationTolerance", {"2", "0.5", "0.12"}, " texels"),
                      ErrorTrend::Falls});
}

// Marschner's terms, multiple scattering and how lights are batched.
void addShadingApproximations(std::vector<Approximation>& matrix) {
    // Single scattering only: the tables' error is the azimuthal terms'.
    matrix.push_back({"marschner:azimuthal",
                      "Marschner's azimuthal terms from 64x64 tables per material, or solved per fragment",
                      {"shadingModel=marschner", "multipleScattering=off"},
                      ladder("marschner:azimuthal", {"tables", "analytic"}, ""),
                      ErrorTrend::Falls});
    // Multiple scattering under the defaults and the high preset (whose deep
    // opacity maps, with more layers, give its transmittance more detail).
    // Both steps differ from the default (auto): each is measured as set.
    for (const bool high : {false, true})
        matrix.push_back({high ? "multipleScattering:high" : "multipleScattering",
                          "light scattered through several fibres (dual scattering), off or on: multiple scattering's "
                          "light against its per-light shading",
                          high ? std::vector<std::string>{"shadingModel=marschner", "quality=high"}
                               : std::vector<std::string>{"shadingModel=marschner"},
                          {{"off", {"multipleScattering=off"}, false},
                           {"dualScattering", {"multipleScattering=dualScattering"}, false}},
                          ErrorTrend::Falls, true, false});
    matrix.push_back({"lightsPerPass",
                      "lights shaded in one pass: passes over the strands, not an approximation (sums are exact "
                      "within 1/255)",
                      {},
                      ladder("lightsPerPass", {"1", "2", "4", "16"}, " lights"),
                      ErrorTrend::Flat});
}

// How thin strands and edges are sampled across a pixel.
void addSamplingApproximations(std::vector<Approximation>& matrix) {
    matrix.push_back({"minPixelWidth",
                      "strands thinner than this many pixels drawn this wide with alpha scaled down: coverage "
                      "against aliasing",
                      {},
                      ladder("minPixelWidth", {"4", "2", "1"}, " px"),
                      ErrorTrend::Falls});
    matrix.push_back({"msaaSamples",
                      "multisampling of the opaque path (under transparency=opaque): edge coverage against samples",
                      {"transparency=opaque"},
                      ladder("msaaSamples", {"0", "2", "4"}, " samples"),
                      ErrorTrend::Falls, true, false});
    matrix.push_back({"supersampling",
                      "N x N samples per pixel, box-filtered: sampling error against N^2 the pixels",
                      {},
                      ladder("supersampling", {"1", "2", "3"}, "x"),
                      ErrorTrend::Falls, true, false});
}

}  // namespace

std::vector<Approximation> accuracyMatrix(bool quick) {
    std::vector<Approximation> matrix;
    addCompositingApproximations(matrix);
    matrix.push_back(tessellationApproximation());
    addShadowApproximations(matrix);
    addShadingApproximations(matrix);
    addSamplingApproximations(matrix);
    if (quick)
        for (Approximation& approximation : matrix) approximation.steps = ends(approximation.steps);
    return matrix;
}

std::vector<Step> presetSteps() {
    std::vector<Step> steps;
    for (Quality quality : {Quality::Preview, Quality::Default, Quality::High, Quality::Reference})
        steps.push_back({std::string("quality=") + toString(quality), {std::string("quality=") + toString(quality)},
                         quality == Quality::Default});
    return steps;
}

}  // namespace hdhair::accuracy
