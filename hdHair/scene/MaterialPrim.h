#pragma once
// A UsdShade material as hdHair reads it: what its surface shader says about
// a strand's base colour and opacity. hdHair shades hair with its own models
// (Kajiya-Kay, Marschner, HdHairAPI parameters); from a bound material it
// takes only what Storm would show, UsdPreviewSurface's diffuseColor and
// opacity, so a groom looks the same colour in both. Every front end (the
// .usda reader, the Hydra plugin) fills this in from its own data; the rules
// for using it live in one place (hdHair/curves/StrandColorSource.h).

#include <string>
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
};

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
};

}  // namespace hdhair
