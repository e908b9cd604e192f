#pragma once
// Quality presets: named sets of the existing render settings, so that a user
// picks a point on the error-versus-time curve (docs/accuracy.md) with one
// word instead of a dozen settings. The `quality` setting names one; a
// setting set explicitly wins over its preset, and so does a complexity above
// low for the settings complexity scales (RenderSettings::origin says which
// chose each value). `default` sets nothing: it is today's defaults exactly.

#include <string>
#include <utility>
#include <vector>

#include "hdHair/plan/SettingTokens.h"

namespace hdhair {

// The NAME=VALUE pairs a preset sets, in a fixed order (README lists them).
const std::vector<std::pair<std::string, std::string>>& presetSettings(Quality quality);

// The value `quality` gives `name`, or nullptr when the preset leaves it alone.
const std::string* presetValue(Quality quality, const std::string& name);

}  // namespace hdhair
