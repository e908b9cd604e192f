#pragma once
// One parsed .usda layer: its metadata and a tree of prim specs, exactly as
// authored (nothing composed yet). StageComposer combines layers into a
// Stage. Internal to hdhair_usda.

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hdHair/usda/Stage.h"
#include "hdHair/usda/Value.h"

namespace hdhair::usda::detail {

enum class ListOpKind { Explicit, Prepend, Append, Add, Delete, Reorder };

// An SdfListOp: an explicit list, or edits (delete/add/prepend/append) to the
// weaker opinions' list. Reorder is parsed and ignored.
template <class T>
struct ListOp {
    bool isExplicit = false;
    std::vector<T> explicitItems, prepended, appended, added, deleted;

    bool empty() const {
        return !isExplicit && prepended.empty() && appended.empty() && added.empty() && deleted.empty();
    }
    void set(ListOpKind kind, std::vector<T> items) {
        switch (kind) {
            case ListOpKind::Explicit: isExplicit = true; explicitItems = std::move(items); break;
            case ListOpKind::Prepend: prepended = std::move(items); break;
            case ListOpKind::Append: appended = std::move(items); break;
            case ListOpKind::Add: added = std::move(items); break;
            case ListOpKind::Delete: deleted = std::move(items); break;
            case ListOpKind::Reorder: break;
        }
    }
    // Applies this (stronger) opinion to the list composed from weaker ones.
    void applyTo(std::vector<T>& result) const {
        auto remove = [&result](const T& item) {
            for (size_t i = 0; i < result.size();) {
                if (result[i] == item) {
                    result.erase(result.begin() + static_cast<std::ptrdiff_t>(i));
                } else {
                    ++i;
                }
            }
        };
        auto contains = [&result](const T& item) {
            for (const T& existing : result) {
                if (existing == item) return true;
            }
            return false;
        };
        if (isExplicit) {
            result.clear();
            for (const T& item : explicitItems) {
                if (!contains(item)) result.push_back(item);
            }
            return;
        }
        for (const T& item : deleted) remove(item);
        for (const T& item : added) {
            if (!contains(item)) result.push_back(item);
        }
        for (size_t i = prepended.size(); i-- > 0;) {
            remove(prepended[i]);
            result.insert(result.begin(), prepended[i]);
        }
        for (const T& item : appended) {
            remove(item);
            result.push_back(item);
        }
    }
};

// A reference or payload: @assetPath@</primPath> (offset = o; scale = s).
struct Reference {
    std::string assetPath;      // empty for an internal reference
    std::string primPath;       // empty: the target layer's defaultPrim
    double offset = 0.0;        // layer offset: parsed, not applied
    double scale = 1.0;
    SourceLocation location;    // where it was authored
    std::string baseDirectory;  // directory of the layer that authored it

    // As SdfReference: items of a list op compare by their authored value.
    bool operator==(const Reference& other) const {
        return assetPath == other.assetPath && primPath == other.primPath;
    }
};

struct SubLayer {
    std::string assetPath;
    double offset = 0.0;  // parsed, not applied
    double scale = 1.0;
    SourceLocation location;
};

struct AttributeSpec {
    std::string name;
    std::string typeName;  // "" when only ".connect" or metadata was authored without a type
    bool isUniform = false;
    bool isCustom = false;
    std::optional<Value> defaultValue;
    bool hasTimeSamples = false;
    std::map<double, Value> timeSamples;
    std::map<std::string, Value> metadata;
    ListOp<std::string> connections;
    SourceLocation location;
    // The directory of this spec's layer, for asset-valued attributes only
    // (other attributes leave it empty and pay nothing): their relative asset
    // paths resolve against it, as OpenUSD resolves them against the layer
    // that authored the value.
    std::string assetDirectory;
};

struct RelationshipSpec {
    std::string name;
    bool isCustom = false;
    ListOp<std::string> targets;
    std::map<std::string, Value> metadata;
    SourceLocation location;
};

struct PrimSpec;

struct VariantSetSpec {
    std::string name;
    std::vector<std::pair<std::string, std::unique_ptr<PrimSpec>>> variants;  // authored order
    SourceLocation location;
};

struct PrimSpec {
    std::string name;  // "" for the pseudo-root
    Specifier specifier = Specifier::Over;
    std::string typeName;
    SourceLocation location;
    std::map<std::string, Value> metadata;  // everything not listed below (kind, active, variants, ...)
    ListOp<Reference> references;
    ListOp<Reference> payloads;
    ListOp<std::string> apiSchemas;
    ListOp<std::string> variantSetNames;
    std::map<std::string, AttributeSpec> attributes;
    std::map<std::string, RelationshipSpec> relationships;
    std::vector<std::unique_ptr<PrimSpec>> children;  // authored order
    std::map<std::string, PrimSpec*> childIndex;
    std::vector<VariantSetSpec> variantSets;

    const PrimSpec* child(const std::string& childName) const {
        auto it = childIndex.find(childName);
        return it == childIndex.end() ? nullptr : it->second;
    }
    const PrimSpec* variant(const std::string& setName, const std::string& variantName) const {
        for (const VariantSetSpec& set : variantSets) {
            if (set.name != setName) continue;
            for (const auto& entry : set.variants) {
                if (entry.first == variantName) return entry.second.get();
            }
        }
        return nullptr;
    }
};

struct Layer {
    std::string identifier;  // names the layer in messages: the path as opened
    std::string directory;   // absolute; relative asset paths resolve against it
    LayerInfo info;
    std::vector<SubLayer> subLayers;
    PrimSpec pseudoRoot;
};

// Parses one layer; throws hdhair::InputError "identifier:line:column: ...".
std::unique_ptr<Layer> parseLayer(std::string_view text, const std::string& identifier,
                                  const std::string& directory);

}  // namespace hdhair::usda::detail
