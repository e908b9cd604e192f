#include "hdHair/usda/SceneReader.h"

#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <unordered_set>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "hdHair/scene/AuthoredValueRepairs.h"
#include "hdHair/scene/SceneValidation.h"
#include "hdHair/usda/MaterialBinding.h"
#include "hdHair/usda/XformOps.h"

namespace hdhair::usda {

namespace {

const std::string kPrimvarsPrefix = "primvars:";
const std::string kIndicesSuffix = ":indices";

bool startsWith(const std::string& text, const std::string& prefix) {
    return text.compare(0, prefix.size(), prefix) == 0;
}

bool endsWith(const std::string& text, const std::string& suffix) {
    return text.size() >= suffix.size() &&
           text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// Thrown while reading one prim; the prim is reported and skipped.
struct SkipPrim {
    std::string where;
    std::string message;
};

// What a prim inherits from its ancestors.
struct Inherited {
    glm::dmat4 world{1.0};
    bool visible = true;
    std::optional<std::string> purpose;  // set once an ancestor authors purpose
    std::string materialBinding;         // the nearest direct binding's target
    const Prim* bindingPrim = nullptr;   // the prim that authored it, for messages
};

// Gprim types hdHair does not draw; reported once each so that a stage that
// relies on them does not silently render empty.
const std::set<std::string> kUnsupportedGprims = {
    "NurbsCurves", "HermiteCurves", "Points", "NurbsPatch", "TetMesh", "Sphere", "Cube",
    "Cylinder", "Cylinder_1", "Cone", "Capsule", "Capsule_1", "Plane", "CylinderLight",
    "PortalLight", "GeometryLight", "PluginLight"};

class Reader {
public:
    Reader(const Stage& stage, double time, Scene& scene, Diagnostics& diagnostics,
           const SceneReadOptions& options)
        : stage_(stage), time_(time), scene_(scene), diagnostics_(diagnostics),
          options_(options) {
        for (const Prim* prim : stage.traverse()) traversed_.insert(prim);
    }

    void readInfo();
    void walk(const Prim& prim, const Inherited& parent);

private:
    // Prim readers; each throws SkipPrim for a value of the wrong type.
    void readCurves(const Prim& prim, const Inherited& state);
    void readMesh(const Prim& prim, const Inherited& state);
    void readCamera(const Prim& prim, const Inherited& state);
    void readLight(const Prim& prim, const Inherited& state, LightType type);
    // The bound material's path after reading it into the scene (once per
    // material); "" with a warning when the target is not a Material.
    std::string useMaterial(const Inherited& state);

    // The value of `name` at the read time; nullopt when the prim has no such
    // attribute or it has no (unblocked) value then.
    std::optional<Value> valueOf(const Prim& prim, const std::string& name) const;
    [[noreturn]] void typeError(const Prim& prim, const std::string& name,
                                const std::string& expected, const Value& found) const;
    void warn(const Prim& prim, const std::string& name, const std::string& message) const;
    // Warns when the colour attribute `name` says in its colorSpace metadata
    // that it is not linear Rec.709: hdHair takes every authored colour as
    // linear Rec.709, as the Hydra plugin must (Hydra hands it no colour
    // space), so the two front ends agree and the metadata is never silently
    // dropped.
    void checkColorSpace(const Prim& prim, const std::string& name) const;

    // The value of the first of `names` that has one, checked to be a numeric
    // scalar of `count` components (SkipPrim naming `expected` otherwise);
    // nullopt when none has a value.
    std::optional<Value> readNumericScalar(const Prim& prim,
                                           std::initializer_list<const char*> names, size_t count,
                                           const char* expected) const;

    // Typed accessors: the value, `fallback` when unauthored, SkipPrim when
    // authored with the wrong type. Each takes the names to try in order.
    float readFloat(const Prim& prim, std::initializer_list<const char*> names, float fallback) const;
    bool readBool(const Prim& prim, std::initializer_list<const char*> names, bool fallback) const;
    glm::vec3 readColor(const Prim& prim, std::initializer_list<const char*> names,
                        glm::vec3 fallback) const;
    std::optional<std::string> readToken(const Prim& prim, const std::string& name) const;
    // The first of `names` with a value, an asset path resolved against the
    // layer that authored it (resolveAssetPath); "" when none has one. A value
    // of another type is a warning and reads as "": an unusable texture leaves
    // a light untextured rather than skipping it.
    std::string readAssetPath(const Prim& prim, std::initializer_list<const char*> names) const;
    std::vector<glm::vec3> readVec3Array(const Prim& prim, const std::string& name) const;
    std::vector<int> readIntArray(const Prim& prim, const std::string& name) const;
    std::vector<float> readFloatArray(const Prim& prim, const std::string& name) const;

    // primvars:NAME (and its indices) as a Primvar; nullopt when it has no
    // value or a non-numeric one. requiredTupleSize 0 accepts any.
    std::optional<Primvar> readPrimvar(const Prim& prim, const std::string& attributeName,
                                       const std::string& primvarName,
                                       Interpolation defaultInterpolation,
                                       int requiredTupleSize, const char* expectedType) const;
    // Every primvars:* attribute, plus `widths`/`normals` attributes when the
    // primvar of that name has no value.
    std::map<std::string, Primvar> readPrimvars(const Prim& prim, bool withWidths) const;

    std::string locationOf(const Prim& prim, const std::string& name) const;

    const Stage& stage_;
    double time_;
    Scene& scene_;
    Diagnostics& diagnostics_;
    SceneReadOptions options_;
    std::unordered_set<const Prim*> traversed_;
    std::set<std::string> reportedTypes_;
    std::map<std::string, bool> materials_;  // binding targets seen: is it a usable Material
};

std::string Reader::locationOf(const Prim& prim, const std::string& name) const {
    const Attribute* attribute = name.empty() ? nullptr : prim.attribute(name);
    return attribute ? attribute->location.toString() : prim.location.toString();
}

std::optional<Value> Reader::valueOf(const Prim& prim, const std::string& name) const {
    const Attribute* attribute = prim.attribute(name);
    if (!attribute) return std::nullopt;
    std::optional<Value> value = attribute->valueAt(time_);
    if (!value || value->isBlocked) return std::nullopt;
    return value;
}

void Reader::typeError(const Prim& prim, const std::string& name, const std::string& expected,
                       const Value& found) const {
    const Attribute* attribute = prim.attribute(name);
    std::string foundType = attribute && !attribute->typeName.empty() ? attribute->typeName
                                                                       : found.typeName;
    throw SkipPrim{locationOf(prim, name),
                   prim.path + "." + name + ": expected " + expected + ", found " + foundType +
                       "; prim skipped"};
}

void Reader::warn(const Prim& prim, const std::string& name, const std::string& message) const {
    diagnostics_.warn(locationOf(prim, name), prim.path + "." + name + ": " + message);
}

void Reader::checkColorSpace(const Prim& prim, const std::string& name) const {
    const Attribute* attribute = prim.attribute(name);
    if (!attribute) return;
    auto metadatum = attribute->metadata.find("colorSpace");
    if (metadatum == attribute->metadata.end()) return;
    const std::string space = metadatum->second.stringOr();
    // Names OpenUSD and common OCIO configs give linear Rec.709.
    for (const char* linearRec709 : {"lin_rec709", "lin_rec709_scene", "lin_srgb", "Linear Rec.709 (sRGB)"})
        if (space == linearRec709) return;
    warn(prim, name,
         "colorSpace '" + space +
             "' is not applied: hdHair takes authored colours as linear Rec.709 (lin_rec709), as its Hydra "
             "plugin does; convert the values to linear Rec.709");
}

std::optional<Value> Reader::readNumericScalar(const Prim& prim,
                                               std::initializer_list<const char*> names,
                                               size_t count, const char* expected) const {
    for (const char* name : names) {
        std::optional<Value> value = valueOf(prim, name);
        if (!value) continue;
        if (!value->isNumeric() || value->isArray || value->numbers.size() != count)
            typeError(prim, name, expected, *value);
        return value;
    }
    return std::nullopt;
}

float Reader::readFloat(const Prim& prim, std::initializer_list<const char*> names,
                        float fallback) const {
    std::optional<Value> value = readNumericScalar(prim, names, 1, "a float");
    return value ? static_cast<float>(value->numbers[0]) : fallback;
}

bool Reader::readBool(const Prim& prim, std::initializer_list<const char*> names,
                      bool fallback) const {
    std::optional<Value> value = readNumericScalar(prim, names, 1, "a bool");
    return value ? value->numbers[0] != 0.0 : fallback;
}

glm::vec3 Reader::readColor(const Prim& prim, std::initializer_list<const char*> names,
                            glm::vec3 fallback) const {
    std::optional<Value> value = readNumericScalar(prim, names, 3, "color3f");
    if (!value) return fallback;
    return glm::vec3(static_cast<float>(value->numbers[0]),
                     static_cast<float>(value->numbers[1]),
                     static_cast<float>(value->numbers[2]));
}

std::optional<std::string> Reader::readToken(const Prim& prim, const std::string& name) const {
    std::optional<Value> value = valueOf(prim, name);
    if (!value) return std::nullopt;
    if (!value->isStringType() || value->isArray || value->strings.size() != 1)
        typeError(prim, name, "token", *value);
    return value->strings[0];
}

std::string Reader::readAssetPath(const Prim& prim, std::initializer_list<const char*> names) const {
    for (const char* name : names) {
        std::optional<Value> value = valueOf(prim, name);
        if (!value) continue;
        if (value->typeName != "asset" || value->strings.size() != 1) {
            warn(prim, name, "expected an asset path (asset " + std::string(name) + " = @file@), found " +
                                 value->typeName + "; ignored");
            return std::string();
        }
        if (value->strings[0].empty()) return std::string();  // @@: authored as no file
        return resolveAssetPath(value->strings[0], prim.attribute(name)->valueDirectoryAt(time_));
    }
    return std::string();
}

std::vector<glm::vec3> Reader::readVec3Array(const Prim& prim, const std::string& name) const {
    std::vector<glm::vec3> result;
    std::optional<Value> value = valueOf(prim, name);
    if (!value) return result;
    // Any three-component numeric array (point3f[], float3[], point3d[], ...)
    // is accepted, as UsdImaging hands each of them to Hydra as a vec3 array.
    if (!value->isNumeric() || !value->isArray || value->tupleSize != 3)
        typeError(prim, name, "point3f[]", *value);
    result.reserve(value->numbers.size() / 3);
    for (size_t i = 0; i + 2 < value->numbers.size(); i += 3) {
        result.emplace_back(static_cast<float>(value->numbers[i]),
                            static_cast<float>(value->numbers[i + 1]),
                            static_cast<float>(value->numbers[i + 2]));
    }
    return result;
}

std::vector<int> Reader::readIntArray(const Prim& prim, const std::string& name) const {
    std::vector<int> result;
    std::optional<Value> value = valueOf(prim, name);
    if (!value) return result;
    if (!value->isNumeric() || !value->isArray || value->tupleSize != 1 ||
        isFloatingPointType(scalarTypeNameOf(value->typeName)))
        typeError(prim, name, "int[]", *value);
    result.reserve(value->numbers.size());
    for (size_t i = 0; i < value->numbers.size(); ++i) {
        const double number = value->numbers[i];
        if (number != std::floor(number)) typeError(prim, name, "int[]", *value);
        if (std::fabs(number) > 2147483647.0)
            throw SkipPrim{locationOf(prim, name), fmt::format("{}.{}: element {} is {:.0f}, beyond a 32-bit int "
                                                               "(at most 2147483647); prim skipped",
                                                               prim.path, name, i, number)};
        result.push_back(static_cast<int>(number));
    }
    return result;
}

std::vector<float> Reader::readFloatArray(const Prim& prim, const std::string& name) const {
    std::vector<float> result;
    std::optional<Value> value = valueOf(prim, name);
    if (!value) return result;
    if (!value->isNumeric() || !value->isArray || value->tupleSize != 1) typeError(prim, name, "float[]", *value);
    result.reserve(value->numbers.size());
    for (double number : value->numbers) result.push_back(static_cast<float>(number));
    return result;
}

std::optional<Primvar> Reader::readPrimvar(const Prim& prim, const std::string& attributeName,
                                           const std::string& primvarName,
                                           Interpolation defaultInterpolation,
                                           int requiredTupleSize,
                                           const char* expectedType) const {
    std::optional<Value> value = valueOf(prim, attributeName);
    if (!value) return std::nullopt;
    if (!value->isNumeric()) {
        if (requiredTupleSize > 0) typeError(prim, attributeName, expectedType, *value);
        return std::nullopt;
    }
    if (requiredTupleSize > 0 && value->tupleSize != requiredTupleSize)
        typeError(prim, attributeName, expectedType, *value);

    const Attribute& attribute = *prim.attribute(attributeName);
    Primvar primvar;
    primvar.name = primvarName;
    primvar.typeName = attribute.typeName.empty() ? value->typeName : attribute.typeName;
    primvar.tupleSize = value->tupleSize > 0 ? value->tupleSize : 1;
    primvar.values.reserve(value->numbers.size());
    for (double number : value->numbers) primvar.values.push_back(static_cast<float>(number));

    primvar.interpolation = defaultInterpolation;
    auto interpolation = attribute.metadata.find("interpolation");
    if (interpolation != attribute.metadata.end()) {
        const std::string token = interpolation->second.stringOr();
        if (parseToken(token, &primvar.interpolation)) {
            primvar.interpolationAuthored = true;
        } else {
            warn(prim, attributeName, unknownTokenRepair("interpolation", token, toString(defaultInterpolation)));
        }
    }
    auto elementSize = attribute.metadata.find("elementSize");
    if (elementSize != attribute.metadata.end()) {
        double size = elementSize->second.numberOr(1.0);
        if (isValidElementSize(size)) {
            primvar.elementSize = static_cast<int>(size);
        } else {
            warn(prim, attributeName, kElementSizeRepair);
        }
    }
    // Only primvars can be indexed; `widths` and `normals` as plain
    // attributes cannot.
    if (startsWith(attributeName, kPrimvarsPrefix))
        primvar.indices = readIntArray(prim, attributeName + kIndicesSuffix);
    return primvar;
}

std::map<std::string, Primvar> Reader::readPrimvars(const Prim& prim, bool withWidths) const {
    std::map<std::string, Primvar> primvars;
    for (const auto& entry : prim.attributes) {
        const std::string& name = entry.first;
        // "primvars:NAME:indices" holds the indices of primvars:NAME, and is
        // not a primvar itself (UsdGeomPrimvar::IsValidPrimvarName).
        if (!startsWith(name, kPrimvarsPrefix) || endsWith(name, kIndicesSuffix)) continue;
        std::string primvarName = name.substr(kPrimvarsPrefix.size());
        if (primvarName.empty()) continue;
        std::optional<Primvar> primvar;
        if (primvarName == "widths") {
            if (!withWidths) continue;
            primvar = readPrimvar(prim, name, primvarName, Interpolation::Constant, 1, "float[]");
        } else if (primvarName == "normals") {
            primvar =
                readPrimvar(prim, name, primvarName, Interpolation::Constant, 3, "normal3f[]");
        } else {
            primvar = readPrimvar(prim, name, primvarName, Interpolation::Constant, 0, "");
        }
        if (primvar) primvars[primvarName] = std::move(*primvar);
    }
    // The schema attributes, used when the primvar of the same name has no
    // value; their interpolation defaults to vertex (UsdGeomCurves::
    // GetWidthsInterpolation, UsdGeomPointBased::GetNormalsInterpolation).
    if (withWidths && !primvars.count("widths")) {
        if (auto widths = readPrimvar(prim, "widths", "widths", Interpolation::Vertex, 1, "float[]"))
            primvars["widths"] = std::move(*widths);
    }
    if (!primvars.count("normals")) {
        if (auto normals =
                readPrimvar(prim, "normals", "normals", Interpolation::Vertex, 3, "normal3f[]"))
            primvars["normals"] = std::move(*normals);
    }
    return primvars;
}

void Reader::readCurves(const Prim& prim, const Inherited& state) {
    CurvesPrim curves;
    curves.path = prim.path;
    curves.sourceFile = stage_.rootLayerPath();
    curves.worldTransform = state.world;
    curves.visible = state.visible;
    // An unknown token keeps the schema fallback (BasisCurves: cubic, bezier,
    // nonperiodic), as UsdImaging's basisCurvesAdapter does.
    if (auto token = readToken(prim, "type")) {
        if (!parseToken(*token, &curves.type))
            warn(prim, "type", unknownTokenRepair("curve type", *token, "cubic"));
    }
    if (auto token = readToken(prim, "basis")) {
        if (!parseToken(*token, &curves.basis))
            warn(prim, "basis", unknownTokenRepair("curve basis", *token, "bezier"));
    }
    if (auto token = readToken(prim, "wrap")) {
        if (!parseToken(*token, &curves.wrap))
            warn(prim, "wrap", unknownTokenRepair("curve wrap", *token, "nonperiodic"));
    }
    curves.curveVertexCounts = readIntArray(prim, "curveVertexCounts");
    curves.points = readVec3Array(prim, "points");
    curves.materialBinding = useMaterial(state);
    curves.primvars = readPrimvars(prim, true);
    checkColorSpace(prim, "primvars:displayColor");
    // The one token primvar hdHair reads (HdHairAPI, constant only).
    if (std::optional<Value> model = valueOf(prim, "primvars:hdHair:shadingModel")) {
        if (model->isStringType() && model->strings.size() == 1)
            curves.shadingModel = model->strings[0];
        else
            warn(prim, "primvars:hdHair:shadingModel", "expected one token (kajiyaKay, marschner or flat); ignored");
    }
    scene_.setCurves(std::move(curves));
}

std::string Reader::useMaterial(const Inherited& state) {
    if (state.materialBinding.empty()) return std::string();
    auto known = materials_.find(state.materialBinding);
    if (known == materials_.end()) {
        const Prim* material = stage_.findPrim(state.materialBinding);
        const bool usable = material && material->typeName == "Material";
        const std::string where = state.bindingPrim->location.toString();
        if (!usable) {
            diagnostics_.warn(where, state.bindingPrim->path + ".material:binding: " + state.materialBinding +
                                         (material ? " is a " + (material->typeName.empty() ? std::string("typeless prim")
                                                                                           : material->typeName)
                                                   : std::string(" does not exist")) +
                                         ", not a Material; the prims below keep their own colours");
        } else {
            std::string problem;
            scene_.setMaterial(readMaterial(stage_, *material, time_, &problem));
            if (!problem.empty()) diagnostics_.warn(material->location.toString(), problem);
            if (const Prim* shader = surfaceShaderOf(stage_, *material)) checkColorSpace(*shader, "inputs:diffuseColor");
        }
        known = materials_.emplace(state.materialBinding, usable).first;
    }
    return known->second ? state.materialBinding : std::string();
}

void Reader::readMesh(const Prim& prim, const Inherited& state) {
    MeshPrim mesh;
    mesh.path = prim.path;
    mesh.sourceFile = stage_.rootLayerPath();
    mesh.worldTransform = state.world;
    mesh.visible = state.visible;
    mesh.points = readVec3Array(prim, "points");
    mesh.faceVertexCounts = readIntArray(prim, "faceVertexCounts");
    mesh.faceVertexIndices = readIntArray(prim, "faceVertexIndices");
    // Tokens are kept as authored: mesh preparation checks them, for every
    // front end alike (hdHair/meshes/MeshTopology.h).
    if (auto scheme = readToken(prim, "subdivisionScheme")) mesh.subdivisionScheme = *scheme;
    if (auto orientation = readToken(prim, "orientation")) mesh.orientation = *orientation;
    if (auto boundary = readToken(prim, "interpolateBoundary")) mesh.interpolateBoundary = *boundary;
    if (auto faceVarying = readToken(prim, "faceVaryingLinearInterpolation"))
        mesh.faceVaryingLinearInterpolation = *faceVarying;
    if (auto triangles = readToken(prim, "triangleSubdivisionRule")) mesh.triangleSubdivisionRule = *triangles;
    mesh.holeIndices = readIntArray(prim, "holeIndices");
    mesh.cornerIndices = readIntArray(prim, "cornerIndices");
    mesh.cornerSharpnesses = readFloatArray(prim, "cornerSharpnesses");
    mesh.creaseIndices = readIntArray(prim, "creaseIndices");
    mesh.creaseLengths = readIntArray(prim, "creaseLengths");
    mesh.creaseSharpnesses = readFloatArray(prim, "creaseSharpnesses");
    mesh.primvars = readPrimvars(prim, false);
    checkColorSpace(prim, "primvars:displayColor");
    scene_.setMesh(std::move(mesh));
}

void Reader::readCamera(const Prim& prim, const Inherited& state) {
    CameraPrim camera;
    camera.path = prim.path;
    camera.worldTransform = state.world;
    if (auto projection = readToken(prim, "projection")) {
        if (*projection == "orthographic") {
            camera.projection = Projection::Orthographic;
        } else if (*projection != "perspective") {
            warn(prim, "projection", "unknown projection '" + *projection + "'; using perspective");
        }
    }
    camera.focalLength = readFloat(prim, {"focalLength"}, camera.focalLength);
    camera.horizontalAperture = readFloat(prim, {"horizontalAperture"}, camera.horizontalAperture);
    camera.verticalAperture = readFloat(prim, {"verticalAperture"}, camera.verticalAperture);
    camera.horizontalApertureOffset =
        readFloat(prim, {"horizontalApertureOffset"}, camera.horizontalApertureOffset);
    camera.verticalApertureOffset =
        readFloat(prim, {"verticalApertureOffset"}, camera.verticalApertureOffset);
    if (std::optional<Value> range = valueOf(prim, "clippingRange")) {
        if (!range->isNumeric() || range->isArray || range->numbers.size() != 2)
            typeError(prim, "clippingRange", "float2", *range);
        camera.clippingRange = glm::vec2(static_cast<float>(range->numbers[0]),
                                         static_cast<float>(range->numbers[1]));
    }
    scene_.setCamera(std::move(camera));
}

void Reader::readLight(const Prim& prim, const Inherited& state, LightType type) {
    LightPrim light;
    light.path = prim.path;
    light.type = type;
    light.worldTransform = state.world;
    light.visible = state.visible;
    // UsdLux 21.02 moved the inputs into the "inputs:" namespace; older files
    // use the bare names, read when the new name has no value. The schema
    // fallbacks apply otherwise: DistantLight's intensity is 50000 ("to
    // approximate the Sun", pxr/usd/usdLux/schema.usda), every other 1.
    const float fallbackIntensity = type == LightType::Distant ? 50000.0f : 1.0f;
    light.intensity = readFloat(prim, {"inputs:intensity", "intensity"}, fallbackIntensity);
    light.exposure = readFloat(prim, {"inputs:exposure", "exposure"}, light.exposure);
    light.color = readColor(prim, {"inputs:color", "color"}, light.color);
    checkColorSpace(prim, "inputs:color");
    checkColorSpace(prim, "color");
    light.enableColorTemperature =
        readBool(prim, {"inputs:enableColorTemperature", "enableColorTemperature"},
                 light.enableColorTemperature);
    light.colorTemperature =
        readFloat(prim, {"inputs:colorTemperature", "colorTemperature"}, light.colorTemperature);
    light.normalize = readBool(prim, {"inputs:normalize", "normalize"}, light.normalize);
    if (type == LightType::Distant)
        light.angle = readFloat(prim, {"inputs:angle", "angle"}, light.angle);
    if (type == LightType::Sphere || type == LightType::Disk)
        light.radius = readFloat(prim, {"inputs:radius", "radius"}, light.radius);
    if (type == LightType::Rect) {
        light.width = readFloat(prim, {"inputs:width", "width"}, light.width);
        light.height = readFloat(prim, {"inputs:height", "height"}, light.height);
    }
    // UsdLuxShapingAPI, applied to any light.
    light.coneAngle =
        readFloat(prim, {"inputs:shaping:cone:angle", "shaping:cone:angle"}, light.coneAngle);
    light.coneSoftness = readFloat(prim, {"inputs:shaping:cone:softness", "shaping:cone:softness"},
                                   light.coneSoftness);
    // UsdLuxShadowAPI, likewise.
    light.shadowEnable = readBool(prim, {"inputs:shadow:enable", "shadow:enable"}, light.shadowEnable);
    if (type == LightType::Dome) {
        light.textureFile = readAssetPath(prim, {"inputs:texture:file", "texture:file"});
        for (const char* name : {"inputs:texture:format", "texture:format"}) {
            if (std::optional<std::string> format = readToken(prim, name)) {
                light.textureFormat = *format;
                break;
            }
        }
    }
    if (repairLight(light, prim.location.toString(), diagnostics_)) scene_.setLight(std::move(light));
}

void Reader::walk(const Prim& prim, const Inherited& parent) {
    // Stage::traverse() leaves out inactive, undefined and abstract prims
    // together with their subtrees; so does this walk.
    if (!traversed_.count(&prim)) return;
    Inherited state = parent;

    LocalTransform local = computeLocalTransform(prim, time_);
    state.world = local.resetsXformStack ? local.matrix : parent.world * local.matrix;

    // Visibility and purpose are read leniently: a value of the wrong type is
    // reported and treated as unauthored, since skipping would have to apply
    // to the whole subtree.
    if (std::optional<Value> visibility = valueOf(prim, "visibility")) {
        if (visibility->isStringType() && !visibility->strings.empty()) {
            const std::string& token = visibility->strings[0];
            if (token == "invisible")
                state.visible = false;
            else if (token != "inherited")
                warn(prim, "visibility", "\"" + token + "\" is neither inherited nor invisible; taken as inherited");
        } else {
            warn(prim, "visibility", "expected token, found " + visibility->typeName + "; ignored");
        }
    }
    if (std::optional<std::string> binding = directMaterialBinding(prim)) {
        state.materialBinding = *binding;
        state.bindingPrim = &prim;
    }
    std::string purpose = "default";
    if (parent.purpose) {
        purpose = *parent.purpose;
    } else if (std::optional<Value> authored = valueOf(prim, "purpose")) {
        if (authored->isStringType() && !authored->strings.empty()) {
            purpose = authored->strings[0];
            state.purpose = purpose;
        } else {
            warn(prim, "purpose", "expected token, found " + authored->typeName + "; ignored");
        }
    }

    const std::string& type = prim.typeName;
    const bool geometry = type == "BasisCurves" || type == "Mesh";
    const bool purposeShown = purpose == "default" ||
                              (purpose == "render" && options_.renderPurpose) ||
                              (purpose == "proxy" && options_.proxyPurpose) ||
                              (purpose == "guide" && options_.guidePurpose);
    try {
        if (geometry && !purposeShown) {
            // Left out by purpose, like a render pass without that render tag.
        } else if (type == "BasisCurves") {
            readCurves(prim, state);
        } else if (type == "Mesh") {
            readMesh(prim, state);
        } else if (type == "Camera") {
            readCamera(prim, state);
        } else if (type == "DistantLight") {
            readLight(prim, state, LightType::Distant);
        } else if (type == "SphereLight") {
            readLight(prim, state, LightType::Sphere);
        } else if (type == "RectLight") {
            readLight(prim, state, LightType::Rect);
        } else if (type == "DiskLight") {
            readLight(prim, state, LightType::Disk);
        } else if (type == "DomeLight") {
            readLight(prim, state, LightType::Dome);
        } else if (kUnsupportedGprims.count(type) && reportedTypes_.insert(type).second) {
            diagnostics_.warn(prim.location.toString(),
                              prim.path + ": hdHair does not render " + type +
                                  " prims; this and any other " + type + " prim are skipped");
        }
    } catch (const SkipPrim& skip) {
        diagnostics_.warn(skip.where, skip.message);
    }

    for (const auto& child : prim.children) walk(*child, state);
}

void Reader::readInfo() {
    const LayerInfo& layer = stage_.info();
    StageInfo& info = scene_.info();
    info.sourceFile = stage_.rootLayerPath();
    if (layer.upAxis == "Z") {
        info.upAxis = UpAxis::Z;
    } else {
        info.upAxis = UpAxis::Y;
        if (layer.upAxis != "Y")
            diagnostics_.warn(stage_.rootLayerPath(),
                              "upAxis must be \"Y\" or \"Z\", found \"" + layer.upAxis +
                                  "\"; using Y");
    }
    info.metersPerUnit = layer.metersPerUnit;
    info.startTimeCode = layer.startTimeCode.value_or(0.0);
    info.endTimeCode = layer.endTimeCode.value_or(info.startTimeCode);
    // UsdStage::GetTimeCodesPerSecond: timeCodesPerSecond, else
    // framesPerSecond when only that is authored, else 24.
    info.timeCodesPerSecond = layer.timeCodesPerSecond;
    if (!layer.metadata.count("timeCodesPerSecond") && layer.metadata.count("framesPerSecond"))
        info.timeCodesPerSecond = layer.framesPerSecond;
}

}  // namespace

void readScene(const Stage& stage, double time, Scene& scene, Diagnostics& diagnostics,
               const SceneReadOptions& options) {
    Reader reader(stage, time, scene, diagnostics, options);
    reader.readInfo();
    Inherited root;
    for (const auto& child : stage.pseudoRoot().children) reader.walk(*child, root);
}

std::unique_ptr<Stage> readSceneFile(const std::string& path, double time, Scene& scene,
                                     Diagnostics& diagnostics, const SceneReadOptions& options) {
    std::unique_ptr<Stage> stage = Stage::open(path);
    readScene(*stage, time, scene, diagnostics, options);
    return stage;
}

}  // namespace hdhair::usda
