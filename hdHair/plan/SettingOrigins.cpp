#include "hdHair/plan/SettingOrigins.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace hdhair {

std::string describeSource(const RenderSettings& settings, const SettingOrigin& origin) {
    switch (origin.source) {
    case SettingSource::Explicit: return "explicit";
    case SettingSource::Complexity: return std::string("complexity ") + toString(settings.complexity());
    case SettingSource::Preset: return std::string("quality=") + toString(settings.quality());
    case SettingSource::Default: break;
    }
    return "default";
}

std::string describeSettingOrigins(const RenderSettings& settings) {
    std::string text = fmt::format("  quality={}, complexity {}\n", toString(settings.quality()),
                                   toString(settings.complexity()));
    for (const SettingDescriptor& descriptor : RenderSettings::descriptors()) {
        const SettingOrigin origin = settings.origin(descriptor.name);
        const bool plainLowComplexity = origin.source == SettingSource::Complexity &&
                                        settings.complexity() == Complexity::Low && origin.overriddenPreset.empty();
        if (origin.source == SettingSource::Default || plainLowComplexity) continue;
        std::string line = fmt::format("  {:<22} {:<12} {}", descriptor.name, settings.getToken(descriptor.name),
                                       describeSource(settings, origin));
        if (!origin.overriddenPreset.empty())
            line += fmt::format(" (wins over quality={}'s {})", toString(settings.quality()), origin.overriddenPreset);
        text += line + "\n";
    }
    return text;
}

nlohmann::json settingOriginsJson(const RenderSettings& settings) {
    nlohmann::json json = nlohmann::json::object();
    for (const SettingDescriptor& descriptor : RenderSettings::descriptors()) {
        const SettingOrigin origin = settings.origin(descriptor.name);
        nlohmann::json entry = {{"source", describeSource(settings, origin)}};
        if (!origin.overriddenPreset.empty()) entry["overriddenPreset"] = origin.overriddenPreset;
        json[descriptor.name] = entry;
    }
    return json;
}

}  // namespace hdhair
