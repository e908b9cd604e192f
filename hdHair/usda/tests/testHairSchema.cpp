// The HdHairAPI schema in schemas/HdHairAPI (see schemas/README.md), checked
// without OpenUSD: its files parse with the embedded reader, every property
// is a documented hdHair primvar, generatedSchema.usda is the flattened form
// of schema.usda, plugInfo.json declares the schema as usdGenSchema does,
// and a stage applying the schema reaches the engine's primvars.

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hdHair/usda/SceneReader.h"

using namespace hdhair;
using namespace hdhair::usda;

namespace {

const std::string kSchemaDir = HDHAIR_SCHEMA_DIR;
const std::string kPrefix = "primvars:hdHair:";

const std::set<std::string> kExpectedProperties = {
    "primvars:hdHair:shadingModel",      "primvars:hdHair:melanin",
    "primvars:hdHair:melaninRedness",    "primvars:hdHair:absorption",
    "primvars:hdHair:eta",               "primvars:hdHair:longitudinalShift",
    "primvars:hdHair:longitudinalWidth", "primvars:hdHair:kajiyaKay:diffuse",
    "primvars:hdHair:kajiyaKay:specular", "primvars:hdHair:kajiyaKay:shininess"};

std::string readText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    EXPECT_TRUE(in) << "cannot open " << path;
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// schema.usda sublayers @usd/schema.usda@, which usdGenSchema finds on
// OpenUSD's resource search path. The embedded reader resolves it next to
// the layer, so the test opens a copy of schema.usda beside a stand-in
// usd/schema.usda that defines the base class it inherits.
std::unique_ptr<Stage> openSchema() {
    namespace fs = std::filesystem;
    fs::path dir = fs::temp_directory_path() / ("hdhair-schema-test-" + std::to_string(::getpid()));
    fs::create_directories(dir / "usd");
    fs::copy_file(kSchemaDir + "/schema.usda", dir / "schema.usda", fs::copy_options::overwrite_existing);
    std::ofstream(dir / "usd" / "schema.usda") << "#usda 1.0\n\nclass \"APISchemaBase\"\n{\n}\n";
    auto stage = Stage::open((dir / "schema.usda").string());
    fs::remove_all(dir);
    return stage;
}

std::string metadataString(const Prim& prim, const std::string& key) {
    auto it = prim.metadata.find(key);
    return it == prim.metadata.end() ? std::string() : it->second.stringOr();
}

std::string attributeDoc(const Attribute& attribute) {
    auto it = attribute.metadata.find("doc");
    return it == attribute.metadata.end() ? std::string() : it->second.stringOr();
}

nlohmann::json readPlugInfo() {
    // Plug (and usdGenSchema) drop lines starting with '#' before parsing.
    std::istringstream in(readText(kSchemaDir + "/plugInfo.json"));
    std::string line, json;
    while (std::getline(in, line)) {
        size_t first = line.find_first_not_of(" \t");
        if (first != std::string::npos && line[first] == '#') continue;
        json += line + "\n";
    }
    return nlohmann::json::parse(json);
}

}  // namespace

TEST(HairSchema, SchemaIsACodelessSingleApplyAPI) {
    auto stage = openSchema();
    const Prim* global = stage->findPrim("/GLOBAL");
    ASSERT_NE(global, nullptr);
    auto customData = global->metadata.find("customData");
    ASSERT_NE(customData, global->metadata.end());
    const Value* skip = customData->second.find("skipCodeGeneration");
    ASSERT_NE(skip, nullptr);
    EXPECT_EQ(skip->numberOr(0.0), 1.0);
    const Value* libraryName = customData->second.find("libraryName");
    ASSERT_NE(libraryName, nullptr);
    EXPECT_EQ(libraryName->stringOr(), "hdHairSchema");

    const Prim* api = stage->findPrim("/HdHairAPI");
    ASSERT_NE(api, nullptr);
    EXPECT_EQ(api->specifier, Specifier::Class);
    EXPECT_EQ(api->typeName, "");
    auto inherits = api->metadata.find("inherits");
    ASSERT_NE(inherits, api->metadata.end());
    EXPECT_EQ(inherits->second.strings, std::vector<std::string>{"/APISchemaBase"});
    auto apiCustomData = api->metadata.find("customData");
    ASSERT_NE(apiCustomData, api->metadata.end());
    const Value* apiSchemaType = apiCustomData->second.find("apiSchemaType");
    ASSERT_NE(apiSchemaType, nullptr);
    EXPECT_EQ(apiSchemaType->stringOr(), "singleApply");
    EXPECT_FALSE(metadataString(*api, "doc").empty());
}

TEST(HairSchema, EveryPropertyIsADocumentedHdHairPrimvar) {
    auto stage = openSchema();
    const Prim* api = stage->findPrim("/HdHairAPI");
    ASSERT_NE(api, nullptr);
    EXPECT_TRUE(api->relationships.empty());
    std::set<std::string> names;
    for (const auto& [name, attribute] : api->attributes) {
        names.insert(name);
        EXPECT_EQ(name.rfind(kPrefix, 0), 0u) << name;
        EXPECT_FALSE(attribute.isUniform) << name << ": primvars may be animated";
        // No fallbacks: unauthored means the render delegate's value.
        EXPECT_FALSE(attribute.defaultValue.has_value()) << name;
        std::string doc = attributeDoc(attribute);
        EXPECT_NE(doc.find("Interpolation:"), std::string::npos) << name;
        EXPECT_NE(doc.find("Unauthored:"), std::string::npos) << name;
        if (name == kPrefix + "shadingModel") {
            EXPECT_EQ(attribute.typeName, "token");
            auto allowed = attribute.metadata.find("allowedTokens");
            ASSERT_NE(allowed, attribute.metadata.end());
            EXPECT_EQ(allowed->second.strings, (std::vector<std::string>{"kajiyaKay", "marschner", "flat"}));
        } else {
            // Arrays, so that uniform, vertex and varying interpolation are possible.
            EXPECT_TRUE(attribute.typeName == "float[]" || attribute.typeName == "color3f[]") << name;
            EXPECT_NE(doc.find("Range:"), std::string::npos) << name;
            EXPECT_NE(doc.find("Default:"), std::string::npos) << name;
            EXPECT_NE(doc.find("vertex"), std::string::npos) << name;
        }
    }
    EXPECT_EQ(names, kExpectedProperties);
}

TEST(HairSchema, GeneratedSchemaIsTheFlattenedClass) {
    auto schema = openSchema();
    auto generated = Stage::open(kSchemaDir + "/generatedSchema.usda");
    EXPECT_TRUE(generated->info().subLayers.empty());
    ASSERT_EQ(generated->pseudoRoot().children.size(), 1u);  // no GLOBAL, no base classes
    const Prim* flat = generated->findPrim("/HdHairAPI");
    const Prim* source = schema->findPrim("/HdHairAPI");
    ASSERT_NE(flat, nullptr);
    ASSERT_NE(source, nullptr);
    EXPECT_EQ(flat->specifier, Specifier::Class);
    // usdGenSchema clears customData and flattens away the inherits arc.
    EXPECT_EQ(flat->metadata.count("customData"), 0u);
    EXPECT_EQ(flat->metadata.count("inherits"), 0u);
    EXPECT_EQ(metadataString(*flat, "doc"), metadataString(*source, "doc"));
    ASSERT_EQ(flat->attributes.size(), source->attributes.size());
    for (const auto& [name, attribute] : source->attributes) {
        const Attribute* copy = flat->attribute(name);
        ASSERT_NE(copy, nullptr) << name;
        EXPECT_EQ(copy->typeName, attribute.typeName) << name;
        EXPECT_EQ(copy->isUniform, attribute.isUniform) << name;
        EXPECT_EQ(copy->defaultValue.has_value(), attribute.defaultValue.has_value()) << name;
        EXPECT_EQ(attributeDoc(*copy), attributeDoc(attribute)) << name;
        std::set<std::string> keys, sourceKeys;
        for (const auto& entry : copy->metadata) keys.insert(entry.first);
        for (const auto& entry : attribute.metadata) sourceKeys.insert(entry.first);
        EXPECT_EQ(keys, sourceKeys) << name;
        if (attribute.metadata.count("allowedTokens")) {
            EXPECT_EQ(copy->metadata.at("allowedTokens").strings, attribute.metadata.at("allowedTokens").strings);
        }
    }
    EXPECT_NE(readText(kSchemaDir + "/generatedSchema.usda").find("GENERATED BY usdGenSchema"), std::string::npos);
}

TEST(HairSchema, PlugInfoDeclaresTheSchema) {
    nlohmann::json info = readPlugInfo();
    ASSERT_TRUE(info.contains("Plugins"));
    ASSERT_EQ(info["Plugins"].size(), 1u);
    const nlohmann::json& plugin = info["Plugins"][0];
    EXPECT_EQ(plugin.at("Name"), "hdHairSchema");  // GLOBAL's libraryName
    EXPECT_EQ(plugin.at("Type"), "resource");     // codeless: nothing to load
    EXPECT_EQ(plugin.at("LibraryPath"), "");
    EXPECT_EQ(plugin.at("Root"), ".");
    EXPECT_EQ(plugin.at("ResourcePath"), ".");   // generatedSchema.usda sits beside plugInfo.json
    const nlohmann::json& types = plugin.at("Info").at("Types");
    ASSERT_EQ(types.size(), 1u);
    // usdGenSchema names the type ProperCase(libraryName) + class name. It
    // must differ from the alias: TfType refuses an alias under UsdSchemaBase
    // equal to the name of a type derived from it, and the schema registry
    // takes a schema's identifier from that alias.
    ASSERT_TRUE(types.contains("HdHairSchemaHdHairAPI"));
    const nlohmann::json& type = types.at("HdHairSchemaHdHairAPI");
    EXPECT_EQ(type.at("alias").at("UsdSchemaBase"), "HdHairAPI");
    EXPECT_EQ(type.at("schemaKind"), "singleApplyAPI");
    EXPECT_EQ(type.at("bases"), nlohmann::json::array({"UsdAPISchemaBase"}));
    EXPECT_EQ(type.at("autoGenerated"), true);
}

TEST(HairSchema, AppliedSchemaPrimvarsReachTheEngine) {
    auto stage = Stage::openFromString(R"(#usda 1.0
def BasisCurves "hair" (
    prepend apiSchemas = ["HdHairAPI"]
)
{
    uniform token type = "linear"
    int[] curveVertexCounts = [2, 2]
    point3f[] points = [(0, 0, 0), (0, 1, 0), (1, 0, 0), (1, 1, 0)]
    float[] primvars:hdHair:melanin = [0.6] (
        interpolation = "constant"
    )
    float[] primvars:hdHair:melaninRedness = [0.1, 0.8] (
        interpolation = "uniform"
    )
    color3f[] primvars:hdHair:absorption = [(0.2, 0.4, 0.8)]
    token primvars:hdHair:shadingModel = "marschner"
}
)",
                                       "applied.usda");
    const Prim* prim = stage->findPrim("/hair");
    ASSERT_NE(prim, nullptr);
    EXPECT_EQ(prim->apiSchemas, std::vector<std::string>{"HdHairAPI"});
    Scene scene;
    Diagnostics diagnostics;
    readScene(*stage, 0.0, scene, diagnostics);
    const CurvesPrim* curves = scene.findCurves("/hair");
    ASSERT_NE(curves, nullptr);
    ASSERT_EQ(curves->primvars.count("hdHair:melanin"), 1u);
    const Primvar& melanin = curves->primvars.at("hdHair:melanin");
    EXPECT_EQ(melanin.interpolation, Interpolation::Constant);
    EXPECT_EQ(melanin.values, std::vector<float>{0.6f});
    const Primvar& redness = curves->primvars.at("hdHair:melaninRedness");
    EXPECT_EQ(redness.interpolation, Interpolation::Uniform);
    EXPECT_EQ(redness.elementCount(), 2u);
    const Primvar& absorption = curves->primvars.at("hdHair:absorption");
    EXPECT_EQ(absorption.interpolation, Interpolation::Constant);  // unauthored interpolation
    EXPECT_EQ(absorption.tupleSize, 3);
    // Token primvars are for materials; the reader leaves them out.
    EXPECT_EQ(curves->primvars.count("hdHair:shadingModel"), 0u);
}
