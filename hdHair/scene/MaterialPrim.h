#pragma once
// A UsdShade material as hdHair reads it: what its surface shader says about
// a strand's base colour and opacity. hdHair shades hair with its own models
// (Kajiya-Kay, Marschner, HdHairAPI parameters); from a bound material it
// takes only what Storm would show, UsdPreviewSurface's diffuseColor and
// opacity, so a groom looks the same colour in both. Every front end (the
// .usda reader, the Hydra plugin) fills this in from its own data; the rules
// for using it live in one place (hdHair/curves/StrandColorSource.h).

#include <string>
#include <tuple>
#include <vector>

namespace hdhair {

// One shader input, as authored or as its connection leads.
struct MaterialInput {
    enum class Source {
        Value,        // `value`: authored, or the shader's default when unauthored
        Primvar,      // connected to a UsdPrimvarReader_*: reads `primvar`, `value` when absent
        Unsupported,  // connected to something hdHair does not evaluate (a texture...)
    };
    Source source = Source::Value;
    std::vector<float> value;  // Value: the input; Primvar: the reader's fallback
    std::string primvar;       // Primvar: the primvar read, without "primvars:"
    std::string connectedTo;   // Unsupported: the upstream shader's id, for messages
    // Every member, for operator==: a scene keeps a prim's version when it is
    // set again unchanged (hdhair-record --frames), so nothing is prepared,
    // uploaded or shadowed again. A member added above must be added here;
    // the size check after the struct is there to say so.
    auto fields() const {
        return std::tie(source, value, primvar, connectedTo);
    }
    bool operator==(const MaterialInput& other) const { return fields() == other.fields(); }
    bool operator!=(const MaterialInput& other) const { return !(*this == other); }
};
static_assert(sizeof(MaterialInput) == 96, "a member was added to MaterialInput: add it to fields() too (x86-64 size)");

struct MaterialPrim {
    std::string path;  // "/World/Looks/hair"
    // The id of the shader behind outputs:surface ("UsdPreviewSurface"), or
    // "" when the material has no universal surface. Only UsdPreviewSurface
    // is read; any other surface leaves the prim's own colours in place.
    std::string surfaceShaderId;
    // UsdPreviewSurface's inputs and their defaults (UsdPreviewSurface spec).
    MaterialInput diffuseColor{MaterialInput::Source::Value, {0.18f, 0.18f, 0.18f}, {}, {}};
    MaterialInput opacity{MaterialInput::Source::Value, {1.0f}, {}, {}};

    bool isPreviewSurface() const { return surfaceShaderId == "UsdPreviewSurface"; }
    // Every member, for operator==: a scene keeps a prim's version when it is
    // set again unchanged (hdhair-record --frames), so nothing is prepared,
    // uploaded or shadowed again. A member added above must be added here;
    // the size check after the struct is there to say so.
    auto fields() const {
        return std::tie(path, surfaceShaderId, diffuseColor, opacity);
    }
    bool operator==(const MaterialPrim& other) const { return fields() == other.fields(); }
    bool operator!=(const MaterialPrim& other) const { return !(*this == other); }
};
static_assert(sizeof(MaterialPrim) == 256, "a member was added to MaterialPrim: add it to fields() too (x86-64 size)");

}  // namespace hdhair
