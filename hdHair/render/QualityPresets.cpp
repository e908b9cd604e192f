#include "hdHair/render/QualityPresets.h"

namespace hdhair {

bool parseQuality(const std::string& name, Quality* out) {
    if (name == "preview") *out = Quality::Preview;
    else if (name == "default") *out = Quality::Default;
    else if (name == "high") *out = Quality::High;
    else if (name == "reference") *out = Quality::Reference;
    else return false;
    return true;
}

const char* toString(Quality quality) {
    switch (quality) {
    case Quality::Preview: return "preview";
    case Quality::Default: return "default";
    case Quality::High: return "high";
    case Quality::Reference: return "reference";
    }
    return "default";
}

const std::vector<std::pair<std::string, std::string>>& presetSettings(Quality quality) {
    // preview: the cheap end of each approximation that still looks like the
    // frame (coarse tessellation, 16 bins as the interactive previews use,
    // smaller shadow maps, every light in one pass, Marschner from tables).
    static const std::vector<std::pair<std::string, std::string>> preview = {
        {"tessellationTolerance", "0.5"}, {"maxSegmentsPerSpan", "4"}, {"sortBins", "16"},
        {"shadowMapResolution", "256"},   {"lightsPerPass", "16"},     {"marschner:azimuthal", "tables"},
    };
    // default: nothing, so `quality=default` renders exactly what no preset does.
    static const std::vector<std::pair<std::string, std::string>> none;
    // high: complexity high's tessellation, the finest bin sort, 7 shadow
    // layers at 1024 texels (on the shadow benchmark's Pareto front, README)
    // and 2 x 2 supersampling, which removes most of the sampling error left.
    static const std::vector<std::pair<std::string, std::string>> high = {
        {"tessellationTolerance", "0.03"}, {"maxSegmentsPerSpan", "32"},   {"sortBins", "1024"},
        {"shadowLayers", "7"},             {"shadowMapResolution", "1024"}, {"supersampling", "2"},
    };
    // reference: the most exact hdHair can be, the yardstick of
    // hdhair-bench --accuracy: exact transparency that fails rather than fall
    // back, reference shadows at the shadow benchmark's 4096 texels, analytic
    // Marschner, the tightest tolerance the setting allows with the most
    // segments a span may get, and 4 x 4 supersampling.
    static const std::vector<std::pair<std::string, std::string>> reference = {
        {"transparency", "exact"},         {"exactOverflow", "fail"},        {"exactMemoryMB", "2048"},
        {"shadowMode", "reference"},       {"shadowMapResolution", "4096"},  {"marschner:azimuthal", "analytic"},
        {"tessellation", "screenError"},   {"tessellationTolerance", "0.001"}, {"maxSegmentsPerSpan", "64"},
        {"supersampling", "4"},
    };
    switch (quality) {
    case Quality::Preview: return preview;
    case Quality::Default: return none;
    case Quality::High: return high;
    case Quality::Reference: return reference;
    }
    return none;
}

const std::string* presetValue(Quality quality, const std::string& name) {
    for (const auto& [setting, value] : presetSettings(quality))
        if (setting == name) return &value;
    return nullptr;
}

}  // namespace hdhair
