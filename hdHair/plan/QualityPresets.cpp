#include "hdHair/plan/QualityPresets.h"

namespace hdhair {

const std::vector<std::pair<std::string, std::string>>& presetSettings(Quality quality) {
    // preview: what the interactive previews draw (InteractivePreview.h),
    // at full size: coarse tessellation, 16 bins, no self-shadowing, every
    // light in one pass, Marschner from tables. Shadows are off because on a
    // groom of many spans their light-view passes are a large share of the
    // frame (docs/accuracy.md, "The presets and the front"), while the other
    // cheap steps save little at small sizes.
    static const std::vector<std::pair<std::string, std::string>> preview = {
        {"tessellationTolerance", "0.5"}, {"maxSegmentsPerSpan", "4"}, {"sortBins", "16"},
        {"shadowMode", "off"},            {"lightsPerPass", "16"},     {"marschner:azimuthal", "tables"},
    };
    // default: nothing, so `quality=default` renders exactly what no preset does.
    static const std::vector<std::pair<std::string, std::string>> none;
    // high: what lowered the error for its time in docs/accuracy.md: 2 x 2
    // supersampling (the largest term at one sample a pixel on every stage),
    // 15 shadow layers (against Cycles' single scattering the layer ladder
    // falls to 15 on dense grooms: docs/accuracy.md, "Against Cycles"), complexity
    // medium's tolerance (curls) and shadow lookups at every fragment. Finer bins and shadow maps are left at the
    // defaults: 1024 bins matched 256 bins' error, and maps finer than 512
    // texels raised it with the layers' depth resolution the limit.
    static const std::vector<std::pair<std::string, std::string>> high = {
        {"tessellationTolerance", "0.06"}, {"maxSegmentsPerSpan", "16"}, {"shadowLayers", "15"},
        {"supersampling", "2"},           {"shadowSampling", "fragment"},
    };
    // reference: the most exact hdHair can be, the yardstick of
    // hdhair-bench --accuracy: exact transparency that fails rather than fall
    // back, reference shadows at the shadow benchmark's 4096 texels, analytic
    // Marschner, the tightest tolerance the setting allows with the most
    // segments a span may get (in the light views too), and 4 x 4
    // supersampling.
    static const std::vector<std::pair<std::string, std::string>> reference = {
        {"transparency", "exact"},         {"exactOverflow", "fail"},        {"exactMemoryMB", "2048"},
        {"shadowMode", "reference"},       {"shadowMapResolution", "4096"},  {"marschner:azimuthal", "analytic"},
        {"tessellation", "screenError"},   {"tessellationTolerance", "0.001"}, {"maxSegmentsPerSpan", "64"},
        {"shadowTessellationTolerance", "0.001"}, {"supersampling", "4"},
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
