#pragma once
// Which of the explicit settings, the complexity level and the quality preset
// chose each setting's value: --explain prints it and --stats keeps it, so a
// user sees what a preset did and what won over it.

#include <string>

#include <nlohmann/json_fwd.hpp>

#include "hdHair/plan/RenderSettings.h"

namespace hdhair {

// "explicit", "complexity high", "quality=reference" or "default".
std::string describeSource(const RenderSettings& settings, const SettingOrigin& origin);

// One line per setting that is not simply its default, in the descriptors'
// order: name, effective value, what chose it, and the preset's value when
// something stronger won over it. Settings complexity low gives their
// default values count as defaults unless a preset lost to them.
std::string describeSettingOrigins(const RenderSettings& settings);

// Every setting's origin, by name: {"source": ..., "overriddenPreset": ...}.
nlohmann::json settingOriginsJson(const RenderSettings& settings);

}  // namespace hdhair
