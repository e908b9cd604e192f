#pragma once
// A composed .usda stage: the embedded reader's answer to UsdStage::Open for
// the subset of USD that hair stages use. See README "Embedded .usda reader"
// for what is and is not supported.
//
// Composition supported: subLayers (stronger first), references and payloads
// (external files with an optional prim path, defaultPrim otherwise, and
// internal references "</Path>"), the selected variant of each variant set,
// list ops with SdfListOp semantics (explicit, prepend, append, add, delete;
// reorder is ignored), def/over/class specifiers. The strongest opinion of
// each attribute, relationship and metadatum wins (dictionaries merge key by
// key). Layer offsets are parsed but not applied; inherits and specializes
// are kept as metadata but not composed.

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hdHair/usda/Value.h"

namespace hdhair::usda {

struct SourceLocation {
    std::string file;
    int line = 0;
    int column = 0;
    std::string toString() const;  // "file:line:column"
};

struct Attribute {
    std::string name;                              // "points", "primvars:displayColor", "xformOp:translate"
    std::string typeName;                          // "point3f[]"
    bool isUniform = false;                        // declared "uniform"
    bool isCustom = false;
    std::optional<Value> defaultValue;             // "= ..." (absent when only timeSamples)
    std::map<double, Value> timeSamples;           // ".timeSamples = {...}"
    std::map<std::string, Value> metadata;         // "interpolation", "elementSize", ...
    std::vector<std::string> connections;          // ".connect = <...>" targets
    SourceLocation location;                       // where the strongest opinion was authored
    // Asset-valued attributes: the directories of the layers whose opinions
    // gave defaultValue and timeSamples; relative asset paths resolve against
    // them (resolveAssetPath). Empty for other attributes.
    std::string defaultValueDirectory;
    std::string timeSamplesDirectory;

    // The value at a time code: time samples win over the default when present;
    // numeric values are linearly interpolated between samples (matrices and
    // vectors component-wise, arrays only when both samples have the same
    // size), other types are held from the sample at or before the time.
    // Before the first or after the last sample, the end sample is held.
    // Quaternions are slerped. A blocked value (None, as the default or as
    // the sample in effect) gives std::nullopt, as does no value at all.
    // A NaN time means UsdTimeCode::Default(): only the default value counts.
    std::optional<Value> valueAt(double time) const;
    bool isTimeVarying() const { return timeSamples.size() > 1; }
    // The directory of the layer whose opinion valueAt(time) reads (time
    // samples or the default, chosen as valueAt chooses).
    const std::string& valueDirectoryAt(double time) const;
};

// An asset path as the embedded reader resolves it (there is no asset
// resolver and no search path): absolute paths as they are, relative ones
// against `directory`, the directory of the layer that authored them; both
// lexically normalised.
std::string resolveAssetPath(const std::string& assetPath, const std::string& directory);

struct Relationship {
    std::string name;
    std::vector<std::string> targets;  // absolute prim or property paths
    SourceLocation location;
};

enum class Specifier { Def, Over, Class };

struct Prim {
    std::string path;                               // "/World/hair"
    std::string name;                               // "hair"
    std::string typeName;                           // "BasisCurves", "" for a typeless prim
    Specifier specifier = Specifier::Def;
    std::string kind;                               // prim metadata "kind"
    std::vector<std::string> apiSchemas;            // prim metadata "apiSchemas"
    bool active = true;                             // prim metadata "active"
    std::map<std::string, Value> metadata;          // every other prim metadatum
    std::map<std::string, Attribute> attributes;    // composed
    std::map<std::string, Relationship> relationships;
    std::vector<std::unique_ptr<Prim>> children;    // in authored order
    const Prim* parent = nullptr;
    SourceLocation location;                        // strongest "def"/"over"/"class" or variant

    const Attribute* attribute(const std::string& attributeName) const;
    const Prim* child(const std::string& childName) const;
};

struct LayerInfo {
    std::string defaultPrim;
    std::string upAxis = "Y";
    double metersPerUnit = 0.01;
    std::optional<double> startTimeCode, endTimeCode;
    double timeCodesPerSecond = 24.0;
    double framesPerSecond = 24.0;
    std::string doc;
    std::vector<std::string> subLayers;         // as authored (asset paths, strongest first)
    std::map<std::string, Value> metadata;      // every layer metadatum as authored (incl. the above)
};

// How much work composing a stage took, counted rather than timed so that
// tests can check how it grows with the stage (a machine's load changes
// seconds, never these counts).
struct CompositionWork {
    uint64_t indexNodes = 0;   // prim index nodes expanded (one per prim and arc)
    uint64_t specLookups = 0;  // steps down a layer's namespace to find a prim spec
    uint64_t opinions = 0;     // prim specs gathered as opinions
    uint64_t cycleChecks = 0;  // path prefixes looked up to keep references from cycling
    uint64_t mappings = 0;     // path mappings stored for opinions (one per index node)
};

class Stage {
public:
    // Reads and composes a stage. Throws hdhair::InputError with
    // "file:line:column: message" for malformed input, and with the path of
    // the layer that names it for a missing sublayer or referenced file.
    static std::unique_ptr<Stage> open(const std::string& path);
    // Same, from text in memory; `identifier` names it in messages and
    // relative asset paths resolve against `baseDirectory`.
    static std::unique_ptr<Stage> openFromString(const std::string& text,
                                                 const std::string& identifier,
                                                 const std::string& baseDirectory = ".");

    const LayerInfo& info() const { return info_; }     // the root layer's metadata
    // open(): the absolute, normalized path; openFromString(): the identifier.
    const std::string& rootLayerPath() const { return rootLayerPath_; }
    const Prim& pseudoRoot() const { return *pseudoRoot_; }
    // Absolute path ("/World/hair"); nullptr when there is no such prim.
    const Prim* findPrim(const std::string& path) const;
    // Every prim below the pseudo-root, depth first in authored order. Inactive
    // prims, prims with the "class" specifier and prims that only have "over"
    // opinions (not defined), each with its descendants, are skipped (as
    // UsdPrimDefaultPredicate does). findPrim still finds them; the children
    // of an inactive prim are not composed at all.
    std::vector<const Prim*> traverse() const;

    const CompositionWork& compositionWork() const { return compositionWork_; }

private:
    LayerInfo info_;
    CompositionWork compositionWork_;
    std::string rootLayerPath_;
    std::unique_ptr<Prim> pseudoRoot_;
    friend class StageComposer;
};

}  // namespace hdhair::usda
