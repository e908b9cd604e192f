#pragma once
// The renderer's quality settings: one table of descriptors (name, type,
// default, range, meaning) that hdhair-record's --setting, --stats and the
// Hydra plugin's GetRenderSettingDescriptors all read, so a setting exists
// everywhere the moment it is added here.

#include <map>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "hdHair/image/ColorSpaces.h"
#include "hdHair/plan/QualityPresets.h"
#include "hdHair/plan/SettingValues.h"

namespace hdhair {

enum class SettingType { Float, Int, Bool, Token };

struct SettingDescriptor {
    std::string name;                 // "maxSegmentsPerSpan"
    SettingType type;
    std::string defaultValue;         // as text, e.g. "8", "kajiyaKay"
    std::string description;          // one line, for --help and usdview
    double minimum = 0.0, maximum = 0.0;  // Float and Int: inclusive range
    std::vector<std::string> tokens;  // Token (or Int): the only values allowed
    SettingField field;               // where SettingValues holds its effective value
};

// usdrecord's --complexity levels; they set the tessellation density and
// the meshes' refine level.
enum class Complexity { Low, Medium, High, VeryHigh };
template <>
struct TokenTable<Complexity> {
    static constexpr std::array<TokenName<Complexity>, 4> names{{{Complexity::Low, "low"},
                                                                 {Complexity::Medium, "medium"},
                                                                 {Complexity::High, "high"},
                                                                 {Complexity::VeryHigh, "veryhigh"}}};
};

// What chose a setting's effective value, strongest first: set explicitly
// (--setting, a Hydra render setting), the complexity level (the settings it
// scales; above low it wins over a preset), the quality preset, or the
// descriptor's default.
enum class SettingSource { Explicit, Complexity, Preset, Default };

struct SettingOrigin {
    SettingSource source = SettingSource::Default;
    // The value the quality preset would have given, when something stronger won.
    std::string overriddenPreset;
};

class RenderSettings {
public:
    RenderSettings();

    static const std::vector<SettingDescriptor>& descriptors();
    static const SettingDescriptor* find(const std::string& name);

    // A complexity level's defaults with "NAME=VALUE" assignments applied in
    // order, as hdhair-record's --complexity and --setting give them; throws
    // as setFromAssignment does.
    static RenderSettings fromAssignments(Complexity complexity, const std::vector<std::string>& assignments);

    // Sets a value from text ("NAME=VALUE" is split by the caller). Throws
    // std::invalid_argument with a one-line reason: unknown name (listing the
    // known ones), or a value of the wrong type or out of range.
    void set(const std::string& name, const std::string& value);
    // Parses "NAME=VALUE".
    void setFromAssignment(const std::string& assignment);
    bool isExplicitlySet(const std::string& name) const { return values_.count(name) > 0; }

    // The `quality` preset in effect (QualityPresets.h).
    Quality quality() const;
    // What chose `name`'s effective value (--explain prints it); throws
    // std::invalid_argument for an unknown name.
    SettingOrigin origin(const std::string& name) const;

    // Tessellation defaults for a complexity level; settings set explicitly win.
    void setComplexity(Complexity complexity) {
        complexity_ = complexity;
        updateValues();
    }
    Complexity complexity() const { return complexity_; }

    // Every setting's effective value, typed (SettingValues.h): what code
    // that needs a particular setting reads.
    const SettingValues& values() const { return typed_; }

    // A setting's effective value by name, for code generic over the table.
    double getFloat(const std::string& name) const;
    int getInt(const std::string& name) const;
    bool getBool(const std::string& name) const;
    std::string getToken(const std::string& name) const;
    // The renderingSpace setting.
    RenderingSpace renderingSpace() const { return typed_.renderingSpace; }

    // Sets a setting by its typed field, as if set explicitly with that
    // value: setValue(&SettingValues::shadowMode, ShadowMode::Off). What
    // previews and tools change, with no name or value spelt as text.
    template <typename T>
    void setValue(T SettingValues::*member, T value) {
        if constexpr (std::is_enum_v<T>) set(descriptorOf(member).name, tokenName(value));
        else set(descriptorOf(member).name, valueText(value));
    }
    // The descriptor of a field of SettingValues.
    template <typename T>
    static const SettingDescriptor& descriptorOf(T SettingValues::*member);

    // Every setting with its effective value, for --stats and --explain.
    nlohmann::json toJson() const;

private:
    static std::string valueText(double value);  // exactly, as from_chars reads it back
    static std::string valueText(int value);
    static std::string valueText(bool value);
    std::string effectiveText(const std::string& name) const;
    // Fills typed_ from the descriptors, after anything that changes an
    // effective value.
    void updateValues();
    std::map<std::string, std::string> values_;  // explicitly set, validated
    Complexity complexity_ = Complexity::Low;
    SettingValues typed_;
};

template <typename T>
const SettingDescriptor& RenderSettings::descriptorOf(T SettingValues::*member) {
    static const SettingValues probe;
    for (const SettingDescriptor& descriptor : descriptors()) {
        if constexpr (std::is_enum_v<T>) {
            const TokenField* field = std::get_if<TokenField>(&descriptor.field);
            if (field && field->address(probe) == &(probe.*member)) return descriptor;
        } else {
            const auto* field = std::get_if<T SettingValues::*>(&descriptor.field);
            if (field && *field == member) return descriptor;
        }
    }
    throw std::logic_error("a SettingValues field without a descriptor");
}

}  // namespace hdhair
