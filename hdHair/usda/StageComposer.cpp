#include "hdHair/usda/StageComposer.h"

#include <algorithm>
#include <deque>
#include <filesystem>
#include <functional>
#include <map>
#include <set>
#include <unordered_set>

#include "hdHair/base/ComposedPrimBound.h"
#include "hdHair/base/CompositionLimits.h"
#include "hdHair/base/InputError.h"
#include "hdHair/base/RegularFile.h"
#include "hdHair/usda/LayerParser.h"

namespace hdhair::usda {

namespace {

namespace fs = std::filesystem;
using detail::AttributeSpec;
using detail::Layer;
using detail::ListOp;
using detail::PrimSpec;
using detail::Reference;
using detail::RelationshipSpec;

constexpr int kMaxNamespaceDepth = 1000;
// Caps that keep hostile stages from exhausting memory or the stack, each
// far beyond what real stages use (README, "The embedded .usda reader"); the
// layer and prim caps are shared with the OpenUSD path (CompositionLimits.h).
constexpr size_t kMaxIndexNodes = 100000;     // layer sites in one prim's index
constexpr size_t kMaxArcDepth = 1000;         // arcs nested in one prim's index (recursion depth)

// ---------------------------------------------------------------- files

std::string absoluteNormal(const fs::path& path) {
    std::error_code ec;
    fs::path absolute = fs::absolute(path, ec);
    if (ec) absolute = path;
    return absolute.lexically_normal().string();
}

// ---------------------------------------------------------------- paths

// "/A" is a prefix of "/A", "/A/B" and "/A.attr", not of "/AB".
bool hasPathPrefix(const std::string& path, const std::string& prefix) {
    if (prefix == "/") return !path.empty() && path[0] == '/';
    if (path.size() < prefix.size() || path.compare(0, prefix.size(), prefix) != 0) return false;
    return path.size() == prefix.size() || path[prefix.size()] == '/' || path[prefix.size()] == '.' ||
           path[prefix.size()] == '{';
}

struct Step {
    bool isVariant = false;
    std::string first;   // prim name, or variant set name
    std::string second;  // variant selection
};

std::string primPathOf(const std::vector<Step>& site) {
    std::string path;
    for (const Step& step : site) {
        if (!step.isVariant) path += "/" + step.first;
    }
    return path.empty() ? "/" : path;
}

std::vector<Step> stepsOf(const std::string& primPath) {
    std::vector<Step> steps;
    size_t pos = 1;
    while (pos < primPath.size()) {
        size_t end = primPath.find('/', pos);
        if (end == std::string::npos) end = primPath.size();
        if (end > pos) steps.push_back(Step{false, primPath.substr(pos, end - pos), std::string()});
        pos = end + 1;
    }
    return steps;
}

// ---------------------------------------------------------------- prim index

struct LayerStack {
    const Layer* root = nullptr;
    std::vector<const Layer*> layers;  // strongest first
};

enum class ArcType { Root = 0, Variant = 1, Reference = 2, Payload = 3 };

struct Node {
    const LayerStack* stack = nullptr;
    std::vector<Step> site;
    ArcType arc = ArcType::Root;
    int depth = 0;    // namespace depth at which the arc was introduced
    int sibling = 0;  // authored order among the arcs of one node
    std::string mapSource, mapTarget;  // the arc maps mapSource (here) to mapTarget (parent); "" = identity
    std::vector<const PrimSpec*> specs;  // strongest first
    std::vector<Node> children;

    // After expand(): children without specs anywhere below are pruned,
    // so a node has specs when it or any remaining child does (O(1), where
    // walking the subtree made a reference chain's composition cubic).
    bool hasSpecs() const { return !specs.empty() || !children.empty(); }
};

// The path mappings from an index node up to the index's root: each arc maps
// its source (there) to its target (in the node above), "" for identity. A
// node's chain shares its parent's: O(1) memory a node, where a copied list
// a node made memory grow with the square of a reference chain's depth.
struct Mapping {
    std::string source, target;
    const Mapping* outer = nullptr;  // toward the root; nullptr above the root
};

std::string mapPath(const std::string& path, const Mapping* mapping) {
    std::string mapped = path;
    for (; mapping; mapping = mapping->outer) {
        if (mapping->source.empty()) continue;
        if (hasPathPrefix(mapped, mapping->source)) mapped = mapping->target + mapped.substr(mapping->source.size());
    }
    return mapped;
}

struct Opinion {
    const PrimSpec* spec;
    const Mapping* mapping;
};

// The index nodes being expanded, from the index's root down: a new
// reference or payload must not point into or above one of them in the same
// layer stack (a cycle). Looked up by path prefix, O(path depth) per arc,
// rather than by walking every ancestor.
class ArcChain {
public:
    void push(const Node& node) {
        const std::string path = primPathOf(node.site);
        nodes_.push_back({node.stack, path});
        exact_[{node.stack, path}] += 1;
        for (const std::string& prefix : prefixesOf(path)) {
            auto& [count, example] = underneath_[{node.stack, prefix}];
            if (count++ == 0) example = path;
        }
    }
    void pop() {
        const auto [stack, path] = nodes_.back();
        nodes_.pop_back();
        if (--exact_[{stack, path}] == 0) exact_.erase({stack, path});
        for (const std::string& prefix : prefixesOf(path))
            if (--underneath_[{stack, prefix}].first == 0) underneath_.erase({stack, prefix});
    }
    size_t depth() const { return nodes_.size(); }
    // An ancestor's path in `stack` that `path` is at, under or above; ""
    // when none. Counts the prefixes it looks up into `lookups`.
    std::string overlapping(const LayerStack* stack, const std::string& path, uint64_t& lookups) const {
        for (const std::string& prefix : prefixesOf(path)) {
            ++lookups;
            if (exact_.count({stack, prefix})) return prefix;
        }
        ++lookups;
        auto below = underneath_.find({stack, path});
        return below == underneath_.end() ? std::string() : below->second.second;
    }

private:
    // "/A/B" -> "/A", "/A/B"; "/" -> "/".
    static std::vector<std::string> prefixesOf(const std::string& path) {
        std::vector<std::string> prefixes;
        for (size_t slash = path.find('/', 1); slash != std::string::npos; slash = path.find('/', slash + 1))
            prefixes.push_back(path.substr(0, slash));
        prefixes.push_back(path);
        return prefixes;
    }
    using Site = std::pair<const LayerStack*, std::string>;
    std::vector<Site> nodes_;
    std::map<Site, int> exact_;
    std::map<Site, std::pair<int, std::string>> underneath_;  // paths under a prefix: how many, and one of them
};

void mergeMetadatum(std::map<std::string, Value>& into, const std::string& key, const Value& weaker) {
    auto it = into.find(key);
    if (it == into.end()) {
        into.emplace(key, weaker);
        return;
    }
    Value& stronger = it->second;
    if (!stronger.isDictionary() || !weaker.isDictionary() || stronger.isBlocked || weaker.isBlocked) return;
    // Dictionaries compose key by key, the stronger value winning.
    std::map<std::string, Value> merged;
    for (size_t i = 0; i < stronger.keys.size(); ++i) merged.emplace(stronger.keys[i], stronger.items[i]);
    for (size_t i = 0; i < weaker.keys.size(); ++i) {
        mergeMetadatum(merged, weaker.keys[i], weaker.items[i]);
        if (std::find(stronger.keys.begin(), stronger.keys.end(), weaker.keys[i]) == stronger.keys.end()) {
            stronger.keys.push_back(weaker.keys[i]);
            stronger.items.push_back(weaker.items[i]);
        }
    }
    for (size_t i = 0; i < stronger.keys.size(); ++i) stronger.items[i] = merged[stronger.keys[i]];
}

class Composer {
public:
    const Layer& addRootLayer(const std::string& key, std::unique_ptr<Layer> layer) {
        const Layer* raw = layer.get();
        layers_[key] = std::move(layer);
        return *raw;
    }

    const Layer& loadLayer(const std::string& absPath, const SourceLocation& from, const char* what) {
        auto it = layers_.find(absPath);
        if (it != layers_.end()) return *it->second;
        if (layers_.size() >= kMaxLayers)
            throw InputError(from.toString() + ": cannot open " + what + " '" + absPath + "': the stage already has " +
                             std::to_string(kMaxLayers) + " layers, the most hdHair reads");
        std::string contents;
        const std::string error = readRegularFile(absPath, contents);
        if (!error.empty())
            throw InputError(from.toString() + ": cannot open " + what + " '" + absPath + "': " + error);
        std::unique_ptr<Layer> layer =
            detail::parseLayer(contents, absPath, fs::path(absPath).parent_path().string());
        const Layer* raw = layer.get();
        layers_[absPath] = std::move(layer);
        return *raw;
    }

    const LayerStack& stackFor(const Layer& root) {
        auto it = stacks_.find(&root);
        if (it != stacks_.end()) return *it->second;
        auto stack = std::make_unique<LayerStack>();
        stack->root = &root;
        std::vector<const Layer*> chain;
        collectSubLayers(root, stack->layers, chain);
        const LayerStack* raw = stack.get();
        stacks_[&root] = std::move(stack);
        return *raw;
    }

    std::unique_ptr<Prim> composeStage(const Layer& rootLayer) {
        Node root;
        root.stack = &stackFor(rootLayer);
        auto pseudoRoot = std::make_unique<Prim>();
        pseudoRoot->path = "/";
        pseudoRoot->specifier = Specifier::Def;
        pseudoRoot->location = SourceLocation{rootLayer.identifier, 1, 1};
        fillSpecs(root);
        composeChildren(*pseudoRoot, root, 0);
        return pseudoRoot;
    }

    const CompositionWork& work() const { return work_; }

    // Refuses, before composing, a stage past kMaxComposedPrims by the
    // bound its layers set (ComposedPrimBound.h): a doubling reference chain
    // is refused in milliseconds rather than composed for minutes.
    void checkComposedPrims(const Layer& rootLayer, const std::string& stagePath) {
        ComposedPrimBound(stagePath, [&](const ComposedPrimBound::Site& site) { return describe(site); })
            .check(siteStackKey(rootLayer));
    }

private:
    // Sites name their layer stack by its root layer's address.
    std::string siteStackKey(const Layer& root) {
        const std::string key = std::to_string(reinterpret_cast<uintptr_t>(&root));
        siteStacks_[key] = &root;
        return key;
    }

    ComposedPrimBound::Specs describe(const ComposedPrimBound::Site& site) {
        const Layer& root = *siteStacks_.at(site.stack);
        ComposedPrimBound::Specs specs;
        std::set<std::string> children;
        const std::vector<Step> steps = stepsOf(site.path);
        for (const Layer* layer : stackFor(root).layers) {
            const PrimSpec* spec = &layer->pseudoRoot;
            for (const Step& step : steps) {
                spec = spec->child(step.first);
                if (!spec) break;
            }
            if (!spec) continue;
            std::vector<const PrimSpec*> withVariants{spec};
            for (const detail::VariantSetSpec& set : spec->variantSets)
                for (const auto& variant : set.variants) withVariants.push_back(variant.second.get());
            for (const PrimSpec* each : withVariants) {
                for (const auto& child : each->children) children.insert(child->name);
                for (const ListOp<Reference>* arcs : {&each->references, &each->payloads}) {
                    const char* what = arcs == &each->payloads ? "payload layer" : "referenced layer";
                    for (const std::vector<Reference>* items :
                         {&arcs->explicitItems, &arcs->prepended, &arcs->appended, &arcs->added})
                        for (const Reference& reference : *items) {
                            const Layer* target = &root;
                            if (!reference.assetPath.empty())
                                target = &loadLayer(resolveAssetPath(reference.assetPath, reference.baseDirectory),
                                                    reference.location, what);
                            std::string path = reference.primPath;
                            // No defaultPrim: composing says so, as an error.
                            if (path.empty() && !target->info.defaultPrim.empty())
                                path = target->info.defaultPrim[0] == '/' ? target->info.defaultPrim
                                                                          : "/" + target->info.defaultPrim;
                            if (!path.empty()) specs.arcs.push_back({siteStackKey(*target), path});
                        }
                }
            }
        }
        specs.children.assign(children.begin(), children.end());
        return specs;
    }

    void collectSubLayers(const Layer& layer, std::vector<const Layer*>& out, std::vector<const Layer*>& chain) {
        if (std::find(out.begin(), out.end(), &layer) != out.end()) return;  // already in the stack
        out.push_back(&layer);
        chain.push_back(&layer);
        for (const detail::SubLayer& sub : layer.subLayers) {
            const std::string path = resolveAssetPath(sub.assetPath, layer.directory);
            const Layer& subLayer = loadLayer(path, sub.location, "sublayer");
            if (std::find(chain.begin(), chain.end(), &subLayer) != chain.end()) {
                throw InputError(sub.location.toString() + ": sublayer cycle: '" + path +
                                 "' is already a sublayer above this one");
            }
            collectSubLayers(subLayer, out, chain);
        }
        chain.pop_back();
    }

    void fillSpecs(Node& node) {
        node.specs.clear();
        for (const Layer* layer : node.stack->layers) {
            const PrimSpec* spec = &layer->pseudoRoot;
            for (const Step& step : node.site) {
                ++work_.specLookups;
                spec = step.isVariant ? spec->variant(step.first, step.second) : spec->child(step.first);
                if (!spec) break;
            }
            if (spec) node.specs.push_back(spec);
        }
    }

    static Node mapToChild(const Node& node, const std::string& name) {
        Node child;
        child.stack = node.stack;
        child.site = node.site;
        child.site.push_back(Step{false, name, std::string()});
        child.arc = node.arc;
        child.depth = node.depth;
        child.sibling = node.sibling;
        child.mapSource = node.mapSource;  // the arc's mapping covers the whole subtree
        child.mapTarget = node.mapTarget;
        child.children.reserve(node.children.size());
        for (const Node& grandChild : node.children) child.children.push_back(mapToChild(grandChild, name));
        return child;
    }

    // The strongest selection for a variant set anywhere in the index so far.
    static const std::string* variantSelection(const Node& node, const std::string& setName) {
        for (const PrimSpec* spec : node.specs) {
            auto it = spec->metadata.find("variants");
            if (it == spec->metadata.end()) continue;
            if (const Value* selection = it->second.find(setName)) {
                if (!selection->strings.empty()) return &selection->strings.front();
            }
        }
        for (const Node& child : node.children) {
            if (const std::string* selection = variantSelection(child, setName)) return selection;
        }
        return nullptr;
    }

    template <class T, class Getter>
    static std::vector<T> composeListOp(const std::vector<const PrimSpec*>& specs, Getter get) {
        std::vector<T> result;
        for (size_t i = specs.size(); i-- > 0;) get(*specs[i]).applyTo(result);
        return result;
    }

    void addReferenceArc(Node& node, const Reference& reference, ArcType arc, int depth, int& sibling,
                         const ArcChain& chain) {
        const char* what = arc == ArcType::Payload ? "payload layer" : "referenced layer";
        const LayerStack* targetStack = node.stack;
        std::string layerName = node.stack->root->identifier;
        if (!reference.assetPath.empty()) {
            const std::string path = resolveAssetPath(reference.assetPath, reference.baseDirectory);
            const Layer& layer = loadLayer(path, reference.location, what);
            targetStack = &stackFor(layer);
            layerName = path;
        }
        std::string targetPath = reference.primPath;
        if (targetPath.empty()) {
            const std::string& defaultPrim = targetStack->root->info.defaultPrim;
            if (defaultPrim.empty()) {
                throw InputError(reference.location.toString() + ": '" + layerName +
                                 "' has no defaultPrim, so the " +
                                 (arc == ArcType::Payload ? "payload" : "reference") +
                                 " must name a prim (@file@</Prim>)");
            }
            targetPath = defaultPrim[0] == '/' ? defaultPrim : "/" + defaultPrim;
        }
        if (targetPath[0] != '/' || targetPath.size() < 2 || targetPath.find_first_of("{}.[]") != std::string::npos) {
            throw InputError(reference.location.toString() + ": unsupported prim path <" + targetPath +
                             "> in a reference (expected an absolute prim path such as </World/asset>)");
        }
        const std::string ancestorPath = chain.overlapping(targetStack, targetPath, work_.cycleChecks);
        if (!ancestorPath.empty()) {
            throw InputError(reference.location.toString() + ": reference cycle: <" + targetPath + "> in '" +
                             layerName + "' is already being composed as <" + ancestorPath + ">");
        }
        Node child;
        child.stack = targetStack;
        child.site = stepsOf(targetPath);
        child.arc = arc;
        child.depth = depth;
        child.sibling = sibling++;
        child.mapSource = targetPath;
        child.mapTarget = primPathOf(node.site);
        fillSpecs(child);
        if (child.specs.empty()) {
            throw InputError(reference.location.toString() + ": " +
                             (arc == ArcType::Payload ? "payload" : "referenced") + " prim <" + targetPath +
                             "> does not exist in '" + layerName + "'");
        }
        node.children.push_back(std::move(child));
    }

    // Fills the node's specs for its site and adds the arcs they author
    // (variants, references, payloads), recursively.
    void expand(Node& node, ArcChain& chain, int depth, const Node& indexRoot) {
        ++work_.indexNodes;
        if (++nodeCount_ > kMaxIndexNodes) {
            throw InputError(node.stack->root->identifier + ": composition of <" + primPathOf(node.site) +
                             "> reaches more than " + std::to_string(kMaxIndexNodes) + " layer sites");
        }
        if (chain.depth() >= kMaxArcDepth) {
            throw InputError(node.stack->root->identifier + ": composition of <" + primPathOf(node.site) +
                             "> nests more than " + std::to_string(kMaxArcDepth) +
                             " references, payloads and variants inside each other");
        }
        fillSpecs(node);
        chain.push(node);
        if (!node.specs.empty()) {
            int sibling = static_cast<int>(node.children.size());
            // Variant sets: the names listed in variantSets, then any other authored set.
            std::vector<std::string> setNames = composeListOp<std::string>(
                node.specs, [](const PrimSpec& spec) -> const ListOp<std::string>& { return spec.variantSetNames; });
            for (size_t i = node.specs.size(); i-- > 0;) {
                for (const detail::VariantSetSpec& set : node.specs[i]->variantSets) {
                    if (std::find(setNames.begin(), setNames.end(), set.name) == setNames.end()) {
                        setNames.push_back(set.name);
                    }
                }
            }
            for (const std::string& setName : setNames) {
                const std::string* selection = variantSelection(indexRoot, setName);
                if (!selection) continue;
                bool authored = false;
                for (const PrimSpec* spec : node.specs) authored = authored || spec->variant(setName, *selection);
                if (!authored) continue;
                Node child;
                child.stack = node.stack;
                child.site = node.site;
                child.site.push_back(Step{true, setName, *selection});
                child.arc = ArcType::Variant;
                child.depth = depth;
                child.sibling = sibling++;
                node.children.push_back(std::move(child));
            }
            const std::vector<Reference> references = composeListOp<Reference>(
                node.specs, [](const PrimSpec& spec) -> const ListOp<Reference>& { return spec.references; });
            for (const Reference& reference : references) {
                addReferenceArc(node, reference, ArcType::Reference, depth, sibling, chain);
            }
            const std::vector<Reference> payloads = composeListOp<Reference>(
                node.specs, [](const PrimSpec& spec) -> const ListOp<Reference>& { return spec.payloads; });
            for (const Reference& payload : payloads) {
                addReferenceArc(node, payload, ArcType::Payload, depth, sibling, chain);
            }
        }
        std::stable_sort(node.children.begin(), node.children.end(), [](const Node& a, const Node& b) {
            if (a.arc != b.arc) return a.arc < b.arc;
            if (a.depth != b.depth) return a.depth > b.depth;  // direct arcs before ancestral ones
            return a.sibling < b.sibling;
        });
        for (Node& child : node.children) expand(child, chain, depth, indexRoot);
        chain.pop();
        node.children.erase(std::remove_if(node.children.begin(), node.children.end(),
                                           [](const Node& child) { return !child.hasSpecs(); }),
                            node.children.end());
    }

    // Strength order: a node, then its arcs' subtrees in order.
    void collectOpinions(const Node& node, const Mapping* outer, std::deque<Mapping>& storage,
                         std::vector<Opinion>& out) {
        storage.push_back(Mapping{node.mapSource, node.mapTarget, outer});
        ++work_.mappings;
        const Mapping* mine = &storage.back();
        work_.opinions += node.specs.size();
        for (const PrimSpec* spec : node.specs) out.push_back(Opinion{spec, mine});
        for (const Node& child : node.children) collectOpinions(child, mine, storage, out);
    }

    static Attribute composeAttribute(const std::string& name,
                                      const std::vector<std::pair<const AttributeSpec*, const Mapping*>>& specs) {
        Attribute attribute;
        attribute.name = name;
        attribute.location = specs.front().first->location;
        bool typed = false;
        bool valueSourceFound = false;
        for (const auto& [spec, mapping] : specs) {
            if (!typed && !spec->typeName.empty()) {
                typed = true;
                attribute.typeName = spec->typeName;
                attribute.isUniform = spec->isUniform;
                attribute.isCustom = spec->isCustom;
            }
            if (!attribute.defaultValue && spec->defaultValue) {
                attribute.defaultValue = spec->defaultValue;
                attribute.defaultValueDirectory = spec->assetDirectory;
            }
            if (!valueSourceFound) {
                // The strongest spec with any value decides: its time samples, or
                // its default (which then hides weaker time samples).
                if (spec->hasTimeSamples) {
                    attribute.timeSamples = spec->timeSamples;
                    attribute.timeSamplesDirectory = spec->assetDirectory;
                    valueSourceFound = true;
                } else if (spec->defaultValue) {
                    valueSourceFound = true;
                }
            }
            for (const auto& [key, value] : spec->metadata) mergeMetadatum(attribute.metadata, key, value);
        }
        for (size_t i = specs.size(); i-- > 0;) {
            const ListOp<std::string>& op = specs[i].first->connections;
            if (op.empty()) continue;
            ListOp<std::string> remapped = op;
            for (auto* list : {&remapped.explicitItems, &remapped.prepended, &remapped.appended, &remapped.added,
                               &remapped.deleted}) {
                for (std::string& path : *list) path = mapPath(path, specs[i].second);
            }
            remapped.applyTo(attribute.connections);
        }
        return attribute;
    }

    static Relationship composeRelationship(
        const std::string& name, const std::vector<std::pair<const RelationshipSpec*, const Mapping*>>& specs) {
        Relationship relationship;
        relationship.name = name;
        relationship.location = specs.front().first->location;
        for (size_t i = specs.size(); i-- > 0;) {
            ListOp<std::string> remapped = specs[i].first->targets;
            for (auto* list : {&remapped.explicitItems, &remapped.prepended, &remapped.appended, &remapped.added,
                               &remapped.deleted}) {
                for (std::string& path : *list) path = mapPath(path, specs[i].second);
            }
            remapped.applyTo(relationship.targets);
        }
        return relationship;
    }

    static void composePrim(Prim& prim, const std::vector<Opinion>& opinions) {
        prim.location = opinions.front().spec->location;
        bool specifierFound = false;
        prim.specifier = Specifier::Over;
        for (const Opinion& opinion : opinions) {
            const PrimSpec& spec = *opinion.spec;
            if (!specifierFound && spec.specifier != Specifier::Over) {
                prim.specifier = spec.specifier;
                specifierFound = true;
            }
            if (prim.typeName.empty()) prim.typeName = spec.typeName;
            for (const auto& [key, value] : spec.metadata) mergeMetadatum(prim.metadata, key, value);
        }
        if (auto it = prim.metadata.find("kind"); it != prim.metadata.end()) {
            prim.kind = it->second.stringOr();
            prim.metadata.erase(it);
        }
        if (auto it = prim.metadata.find("active"); it != prim.metadata.end()) {
            prim.active = it->second.isBlocked || it->second.numberOr(1.0) != 0.0;
            prim.metadata.erase(it);
        }
        std::vector<const PrimSpec*> specs;
        for (const Opinion& opinion : opinions) specs.push_back(opinion.spec);
        prim.apiSchemas = composeListOp<std::string>(
            specs, [](const PrimSpec& spec) -> const ListOp<std::string>& { return spec.apiSchemas; });
        std::vector<std::string> variantSets = composeListOp<std::string>(
            specs, [](const PrimSpec& spec) -> const ListOp<std::string>& { return spec.variantSetNames; });
        if (!variantSets.empty()) {
            Value value;
            value.typeName = "string[]";
            value.isArray = true;
            value.strings = std::move(variantSets);
            prim.metadata["variantSets"] = std::move(value);
        }

        std::map<std::string, std::vector<std::pair<const AttributeSpec*, const Mapping*>>> attributes;
        std::map<std::string, std::vector<std::pair<const RelationshipSpec*, const Mapping*>>> relationships;
        for (const Opinion& opinion : opinions) {
            for (const auto& [name, spec] : opinion.spec->attributes) {
                attributes[name].emplace_back(&spec, opinion.mapping);
            }
            for (const auto& [name, spec] : opinion.spec->relationships) {
                relationships[name].emplace_back(&spec, opinion.mapping);
            }
        }
        for (const auto& [name, specList] : attributes) prim.attributes[name] = composeAttribute(name, specList);
        for (const auto& [name, specList] : relationships) {
            prim.relationships[name] = composeRelationship(name, specList);
        }
    }

    void composeChildren(Prim& parent, const Node& parentIndex, int depth) {
        if (depth >= kMaxNamespaceDepth) {
            throw InputError(parent.location.toString() + ": prim <" + parent.path + "> is nested deeper than " +
                             std::to_string(kMaxNamespaceDepth) + " levels");
        }
        // Child names: weakest opinions first, stronger ones appending new names.
        std::vector<Opinion> opinions;
        std::deque<Mapping> storage;
        collectOpinions(parentIndex, nullptr, storage, opinions);
        std::vector<std::string> names;
        std::unordered_set<std::string> seen;
        for (size_t i = opinions.size(); i-- > 0;) {
            for (const auto& child : opinions[i].spec->children) {
                if (seen.insert(child->name).second) names.push_back(child->name);
            }
        }
        for (const std::string& name : names) {
            Node index = mapToChild(parentIndex, name);
            ArcChain chain;
            nodeCount_ = 0;
            expand(index, chain, depth + 1, index);
            if (!index.hasSpecs()) continue;
            std::vector<Opinion> childOpinions;
            std::deque<Mapping> childStorage;
            collectOpinions(index, nullptr, childStorage, childOpinions);
            if (++composedPrims_ > kMaxComposedPrims)
                throw InputError(parent.location.toString() + ": the stage composes more than " +
                                 std::to_string(kMaxComposedPrims) + " prims, the most hdHair reads");
            auto prim = std::make_unique<Prim>();
            prim->name = name;
            prim->path = (parent.path == "/" ? "/" : parent.path + "/") + name;
            prim->parent = &parent;
            composePrim(*prim, childOpinions);
            Prim* raw = prim.get();
            parent.children.push_back(std::move(prim));
            if (raw->active) composeChildren(*raw, index, depth + 1);
        }
    }

    std::map<std::string, std::unique_ptr<Layer>> layers_;
    std::map<const Layer*, std::unique_ptr<LayerStack>> stacks_;
    size_t nodeCount_ = 0;
    size_t composedPrims_ = 0;
    std::map<std::string, const Layer*> siteStacks_;  // ComposedPrimBound's sites
    CompositionWork work_;
};

}  // namespace

std::unique_ptr<Stage> StageComposer::openFile(const std::string& path) {
    std::string contents;
    const std::string error = readRegularFile(path, contents);
    if (!error.empty()) throw InputError("cannot open '" + path + "': " + error);
    const std::string absolute = absoluteNormal(path);
    Composer composer;
    const Layer& root = composer.addRootLayer(
        absolute, detail::parseLayer(contents, path, fs::path(absolute).parent_path().string()));
    composer.checkComposedPrims(root, path);
    auto stage = std::make_unique<Stage>();
    stage->pseudoRoot_ = composer.composeStage(root);
    stage->info_ = root.info;
    stage->rootLayerPath_ = absolute;
    stage->compositionWork_ = composer.work();
    return stage;
}

std::unique_ptr<Stage> StageComposer::openText(const std::string& text, const std::string& identifier,
                                               const std::string& baseDirectory) {
    Composer composer;
    const Layer& root = composer.addRootLayer(
        std::string("\x01memory:") + identifier,
        detail::parseLayer(text, identifier, absoluteNormal(baseDirectory.empty() ? "." : baseDirectory)));
    composer.checkComposedPrims(root, identifier);
    auto stage = std::make_unique<Stage>();
    stage->pseudoRoot_ = composer.composeStage(root);
    stage->info_ = root.info;
    stage->rootLayerPath_ = identifier;
    stage->compositionWork_ = composer.work();
    return stage;
}

}  // namespace hdhair::usda
