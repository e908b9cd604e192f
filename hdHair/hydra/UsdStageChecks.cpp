#include "hdHair/hydra/UsdStageChecks.h"

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <stdexcept>

#include <fmt/format.h>

#include "pxr/usd/ar/resolver.h"
#include "pxr/usd/pcp/errors.h"
#include "pxr/usd/sdf/layerUtils.h"
#include "pxr/usd/sdf/primSpec.h"
#include "pxr/usd/sdf/variantSetSpec.h"
#include "pxr/usd/sdf/variantSpec.h"
#include "pxr/usd/usd/primRange.h"
#include "pxr/usd/usdGeom/basisCurves.h"
#include "pxr/usd/usdGeom/primvarsAPI.h"
#include "pxr/usd/usdGeom/tokens.h"

#include "hdHair/base/ComposedPrimBound.h"
#include "hdHair/base/CompositionLimits.h"
#include "hdHair/base/InputError.h"
#include "hdHair/base/PrintableText.h"
#include "hdHair/base/RegularFile.h"
#include "hdHair/hydra/HydraCamera.h"
#include "hdHair/scene/AuthoredValueRepairs.h"
#include "hdHair/scene/CurvesPrim.h"
#include "hdHair/scene/Primvar.h"

PXR_NAMESPACE_USING_DIRECTIVE

namespace hdhair::hydra {
namespace {

// OpenUSD's messages can span lines; an error or warning here is one line.
std::string oneLine(std::string text) {
    for (char& c : text)
        if (c == '\n' || c == '\r') c = ' ';
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text;
}

bool sameFile(const std::string& a, const std::string& b) {
    std::error_code error;
    return std::filesystem::equivalent(a, b, error) && !error;
}

// Every layer a stage reaches, opened once and checked, described to
// ComposedPrimBound site by site.
class LayerGraph {
public:
    LayerGraph(std::string stagePath, std::function<std::vector<std::string>()> takeErrors)
        : stagePath_(std::move(stagePath)), takeErrors_(std::move(takeErrors)) {}

    SdfLayerRefPtr openRoot() {
        if (std::string problem = regularFileProblem(stagePath_); !problem.empty())
            throw InputError(stagePath_ + ": cannot open the stage: " + problem);
        checkVersion(stagePath_, stagePath_);
        SdfLayerRefPtr root = SdfLayer::FindOrOpen(stagePath_);
        if (!root) throw InputError(layerOpenFailure(stagePath_, takeErrors_()));
        remember(root);
        return root;
    }

    ComposedPrimBound::Specs describe(const ComposedPrimBound::Site& site) {
        const SdfLayerHandle root = byIdentifier_.at(site.stack);
        const SdfPath path(site.path);
        ComposedPrimBound::Specs specs;
        std::set<std::string> children;
        auto target = [&](const SdfLayerHandle& layer, const std::string& assetPath, const SdfPath& primPath,
                          const char* what) {
            SdfLayerHandle targetRoot = root;
            if (!assetPath.empty()) {
                SdfLayerRefPtr opened = open(layer, assetPath, what);
                if (!opened) return;
                targetRoot = opened;
            }
            SdfPath targetPath = primPath;
            if (targetPath.IsEmpty()) {
                const TfToken defaultPrim = targetRoot->GetDefaultPrim();
                if (defaultPrim.IsEmpty()) return;
                targetPath = SdfPath::AbsoluteRootPath().AppendChild(defaultPrim);
            }
            if (!targetPath.IsAbsolutePath()) targetPath = targetPath.MakeAbsolutePath(path);
            specs.arcs.push_back({targetRoot->GetIdentifier(), targetPath.StripAllVariantSelections().GetString()});
        };
        for (const SdfLayerHandle& layer : layerStack(root)) {
            if (path.IsAbsoluteRootPath()) {
                for (const SdfPrimSpecHandle& child : layer->GetRootPrims()) children.insert(child->GetName());
                continue;
            }
            for (const SdfPrimSpecHandle& spec : specsAt(layer, path)) {
                for (const SdfPrimSpecHandle& child : spec->GetNameChildren()) children.insert(child->GetName());
                std::vector<SdfReference> references;
                spec->GetReferenceList().ApplyEditsToList(&references);
                for (const SdfReference& reference : references)
                    target(layer, reference.GetAssetPath(), reference.GetPrimPath(), "reference");
                std::vector<SdfPayload> payloads;
                spec->GetPayloadList().ApplyEditsToList(&payloads);
                for (const SdfPayload& payload : payloads)
                    target(layer, payload.GetAssetPath(), payload.GetPrimPath(), "payload");
                std::vector<SdfPath> classes;
                spec->GetInheritPathList().ApplyEditsToList(&classes);
                spec->GetSpecializesList().ApplyEditsToList(&classes);
                for (const SdfPath& base : classes) target(layer, std::string(), base, "inherit");
            }
        }
        specs.children.assign(children.begin(), children.end());
        return specs;
    }

    std::vector<SdfLayerRefPtr> layers() const { return layers_; }

private:
    void remember(const SdfLayerRefPtr& layer) {
        if (layers_.size() >= kMaxLayers)
            throw InputError(fmt::format("{}: the stage already has {} layers, the most hdHair reads", stagePath_,
                                         kMaxLayers));
        layers_.push_back(layer);
        byIdentifier_[layer->GetIdentifier()] = layer;
    }

    // A text layer whose header names another version: OpenUSD reads it
    // with a warning that it "may parse correctly and yield incorrect
    // results"; hdHair refuses it, as the embedded reader does, rather than
    // render a picture that may be wrong.
    static void checkVersion(const std::string& file, const std::string& shown) {
        std::ifstream stream(file, std::ios::binary);
        char header[32] = {};
        stream.read(header, sizeof header - 1);
        const std::string text(header, size_t(stream.gcount()));
        if (text.rfind("#usda ", 0) != 0) return;
        const std::string version = text.substr(6, text.find_first_of("\r\n ", 6) - 6);
        if (version != "1.0")
            throw InputError(fmt::format("{}:1:7: unsupported usda version '{}' (expected '1.0')", shown,
                                         printableText(version)));
    }

    // The layer `assetPath` names from `from`; null when it does not resolve
    // (OpenUSD then reports the arc as a composition error, an error here).
    SdfLayerRefPtr open(const SdfLayerHandle& from, const std::string& assetPath, const char* what) {
        const std::string identifier = SdfComputeAssetPathRelativeToLayer(from, assetPath);
        if (identifier.empty()) return nullptr;
        if (auto known = byIdentifier_.find(identifier); known != byIdentifier_.end()) return known->second;
        const ArResolvedPath resolved = ArGetResolver().Resolve(identifier);
        if (resolved.empty()) return nullptr;
        if (std::string problem = regularFileProblem(resolved.GetPathString()); !problem.empty())
            throw InputError(fmt::format("{}: cannot open {} @{}@: {}", from->GetIdentifier(), what, assetPath, problem));
        checkVersion(resolved.GetPathString(), resolved.GetPathString());
        SdfLayerRefPtr layer = SdfLayer::FindOrOpen(identifier);
        if (!layer) throw InputError(layerOpenFailure(resolved.GetPathString(), takeErrors_()));
        remember(layer);
        return layer;
    }

    // The root and its sublayers, strongest first.
    const std::vector<SdfLayerHandle>& layerStack(const SdfLayerHandle& root) {
        auto found = stacks_.find(root->GetIdentifier());
        if (found != stacks_.end()) return found->second;
        std::vector<SdfLayerHandle> stack;
        std::set<std::string> seen;
        std::function<void(const SdfLayerHandle&, int)> add = [&](const SdfLayerHandle& layer, int depth) {
            // A cycle, or nesting past the cap: OpenUSD reports the cycle.
            if (!seen.insert(layer->GetIdentifier()).second || depth > kMaxCompositionNesting) return;
            stack.push_back(layer);
            for (const std::string& path : layer->GetSubLayerPaths())
                if (SdfLayerRefPtr sublayer = open(layer, path, "sublayer")) add(sublayer, depth + 1);
        };
        add(root, 0);
        return stacks_[root->GetIdentifier()] = std::move(stack);
    }

    // The prim specs at `path` in `layer`: the prim's own and its variants'.
    static std::vector<SdfPrimSpecHandle> specsAt(const SdfLayerHandle& layer, const SdfPath& path) {
        std::vector<SdfPrimSpecHandle> specs;
        SdfPrimSpecHandle spec = layer->GetPrimAtPath(path);
        if (!spec) return specs;
        specs.push_back(spec);
        const SdfVariantSetSpecHandleVector variantSets = spec->GetVariantSets();
        for (const SdfVariantSetSpecHandle& variantSet : variantSets)
            for (const SdfVariantSpecHandle& variant : variantSet->GetVariants())
                if (SdfPrimSpecHandle variantPrim = variant->GetPrimSpec()) specs.push_back(variantPrim);
        return specs;
    }

    std::string stagePath_;
    std::function<std::vector<std::string>()> takeErrors_;
    std::vector<SdfLayerRefPtr> layers_;
    std::map<std::string, SdfLayerRefPtr> byIdentifier_;  // the layers above, by identifier
    std::map<std::string, std::vector<SdfLayerHandle>> stacks_;
};

}  // namespace

std::string layerOpenFailure(const std::string& stagePath, const std::vector<std::string>& errors) {
    // Sdf's text format: "syntax error at 'x' in </prim> on line 4 in file /path/f.usda".
    static const std::regex located(R"(^(.*) on line ([0-9]+) in file (.+)$)");
    for (const std::string& error : errors) {
        std::smatch match;
        const std::string line = oneLine(error);
        if (!std::regex_match(line, match, located)) continue;
        const std::string file = sameFile(match[3].str(), stagePath) ? stagePath : match[3].str();
        return file + ":" + match[2].str() + ": " + match[1].str();
    }
    for (const std::string& error : errors)
        if (error.rfind("Failed to open layer", 0) != 0 && error.rfind("Cannot open layer", 0) != 0)
            return stagePath + ": OpenUSD cannot open it: " + oneLine(error);
    return stagePath + ": OpenUSD cannot open it" + (errors.empty() ? std::string() : ": " + oneLine(errors.front()));
}

std::vector<SdfLayerRefPtr> openStageLayers(const std::string& stagePath,
                                            const std::function<std::vector<std::string>()>& takeErrors) {
    LayerGraph graph(stagePath, takeErrors);
    SdfLayerRefPtr root = graph.openRoot();
    ComposedPrimBound(stagePath, [&](const ComposedPrimBound::Site& site) { return graph.describe(site); })
        .check(root->GetIdentifier());
    return graph.layers();
}

std::string compositionProblem(const UsdStageRefPtr& stage) {
    const PcpErrorVector errors = stage->GetCompositionErrors();
    if (errors.empty()) return std::string();
    std::string text = "composition error: " + oneLine(errors.front()->ToString());
    if (errors.size() > 1) text += fmt::format(" (and {} more)", errors.size() - 1);
    return text;
}

void warnAboutCurveTokens(const UsdStageRefPtr& stage, const std::string& stagePath,
                          const std::function<void(const std::string&, const std::string&)>& warn) {
    for (const UsdPrim& prim : stage->Traverse()) {
        if (!prim.IsA<UsdGeomBasisCurves>()) continue;
        const std::string path = prim.GetPath().GetString();
        UsdGeomBasisCurves curves(prim);
        TfToken value;
        CurveType type;
        CurveBasis basis;
        CurveWrap wrap;
        if (curves.GetTypeAttr().HasAuthoredValue() && curves.GetTypeAttr().Get(&value) &&
            !parseToken(value.GetString(), &type))
            warn(stagePath, path + ".type: " + unknownTokenRepair("curve type", value.GetString(), "cubic"));
        if (curves.GetBasisAttr().HasAuthoredValue() && curves.GetBasisAttr().Get(&value) &&
            !parseToken(value.GetString(), &basis))
            warn(stagePath, path + ".basis: " + unknownTokenRepair("curve basis", value.GetString(), "bezier"));
        if (curves.GetWrapAttr().HasAuthoredValue() && curves.GetWrapAttr().Get(&value) &&
            !parseToken(value.GetString(), &wrap))
            warn(stagePath, path + ".wrap: " + unknownTokenRepair("curve wrap", value.GetString(), "nonperiodic"));
        // Primvars default to constant interpolation, the widths and
        // normals attributes to vertex (as the embedded reader reads them).
        std::vector<std::pair<UsdAttribute, const char*>> attributes;
        for (const UsdGeomPrimvar& primvar : UsdGeomPrimvarsAPI(prim).GetAuthoredPrimvars())
            attributes.emplace_back(primvar.GetAttr(), "constant");
        attributes.emplace_back(curves.GetWidthsAttr(), "vertex");
        attributes.emplace_back(curves.GetNormalsAttr(), "vertex");
        for (const auto& [attribute, fallback] : attributes) {
            const std::string where = path + "." + attribute.GetName().GetString() + ": ";
            TfToken interpolation;
            Interpolation parsed;
            if (attribute.GetMetadata(UsdGeomTokens->interpolation, &interpolation) &&
                !parseToken(interpolation.GetString(), &parsed))
                warn(stagePath, where + unknownTokenRepair("interpolation", interpolation.GetString(), fallback));
            VtValue elementSize;
            if (attribute.GetMetadata(UsdGeomTokens->elementSize, &elementSize)) {
                const double size = elementSize.IsHolding<int>() ? double(elementSize.UncheckedGet<int>())
                                    : elementSize.CanCast<double>() ? elementSize.Cast<double>().UncheckedGet<double>()
                                                                    : 0.0;
                if (!isValidElementSize(size)) warn(stagePath, where + kElementSizeRepair);
            }
        }
    }
}

CameraPrim cameraPrimAt(const UsdGeomCamera& camera, UsdTimeCode time) {
    CameraPrim prim;
    prim.path = camera.GetPath().GetString();
    TfToken projection;
    if (camera.GetProjectionAttr().Get(&projection, time) && projection == UsdGeomTokens->orthographic)
        prim.projection = Projection::Orthographic;
    camera.GetFocalLengthAttr().Get(&prim.focalLength, time);
    camera.GetHorizontalApertureAttr().Get(&prim.horizontalAperture, time);
    camera.GetVerticalApertureAttr().Get(&prim.verticalAperture, time);
    camera.GetHorizontalApertureOffsetAttr().Get(&prim.horizontalApertureOffset, time);
    camera.GetVerticalApertureOffsetAttr().Get(&prim.verticalApertureOffset, time);
    GfVec2f clipping;
    if (camera.GetClippingRangeAttr().Get(&clipping, time)) prim.clippingRange = {clipping[0], clipping[1]};
    prim.worldTransform = matrixFromGf(camera.ComputeLocalToWorldTransform(time).data());
    return prim;
}

}  // namespace hdhair::hydra
