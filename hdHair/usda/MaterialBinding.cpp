#include "hdHair/usda/MaterialBinding.h"

namespace hdhair::usda {

namespace {

// "/Looks/hair/Surface.outputs:surface" -> ("/Looks/hair/Surface", "outputs:surface").
std::pair<std::string, std::string> splitPropertyPath(const std::string& path) {
    const size_t dot = path.rfind('.');
    if (dot == std::string::npos) return {path, std::string()};
    return {path.substr(0, dot), path.substr(dot + 1)};
}

std::string shaderId(const Prim& shader, double time) {
    const Attribute* id = shader.attribute("info:id");
    if (!id) return std::string();
    std::optional<Value> value = id->valueAt(time);
    return value && value->isStringType() ? value->stringOr() : std::string();
}

class MaterialInputReader {
public:
    MaterialInputReader(const Stage& stage, double time, std::string* problem)
        : stage_(stage), time_(time), problem_(problem) {}

    // A shader input as its value, or what the connection leads to. Interface
    // inputs of Materials and NodeGraphs are followed (a few hops: a cycle
    // stops there); `defaults` stays when nothing usable is authored.
    MaterialInput read(const Prim& shader, const std::string& inputName, MaterialInput defaults) const {
        const Prim* prim = &shader;
        std::string name = inputName;
        for (int hop = 0; hop < 8; ++hop) {
            const Attribute* attribute = prim->attribute(name);
            if (!attribute) return defaults;
            if (attribute->connections.empty()) return valueOf(*prim, *attribute, defaults);
            auto [upstreamPath, upstreamProperty] = splitPropertyPath(attribute->connections.front());
            const Prim* upstream = stage_.findPrim(upstreamPath);
            if (!upstream) {
                note(prim->path + "." + name + " connects to " + attribute->connections.front() +
                     ", which does not exist");
                return defaults;
            }
            if (upstream->typeName == "Material" || upstream->typeName == "NodeGraph") {
                prim = upstream;  // an interface input (or a node graph output): follow it
                name = upstreamProperty;
                continue;
            }
            const std::string id = shaderId(*upstream, time_);
            if (id.rfind("UsdPrimvarReader_", 0) == 0) {
                MaterialInput input{MaterialInput::Source::Primvar, {}, {}, {}};
                if (const Attribute* varname = upstream->attribute("inputs:varname")) {
                    std::optional<Value> value = varname->valueAt(time_);
                    if (value && value->isStringType()) input.primvar = value->stringOr();
                }
                MaterialInput fallback = read(*upstream, "inputs:fallback", MaterialInput{});
                input.value = fallback.source == MaterialInput::Source::Value ? fallback.value
                                                                              : std::vector<float>();
                // UsdPrimvarReader's own default fallback is zero.
                if (input.value.empty()) input.value.assign(defaults.value.size(), 0.0f);
                return input;
            }
            return MaterialInput{MaterialInput::Source::Unsupported, {}, {}, id.empty() ? upstream->typeName : id};
        }
        note(shader.path + "." + inputName + ": its connections do not end; using the default");
        return defaults;
    }

private:
    MaterialInput valueOf(const Prim& prim, const Attribute& attribute, MaterialInput defaults) const {
        std::optional<Value> value = attribute.valueAt(time_);
        if (!value || value->isBlocked) return defaults;
        if (!value->isNumeric() || value->isArray) {
            note(prim.path + "." + attribute.name + ": expected a number or colour, found " + value->typeName +
                 "; using the default");
            return defaults;
        }
        MaterialInput input{MaterialInput::Source::Value, {}, {}, {}};
        for (double number : value->numbers) input.value.push_back(static_cast<float>(number));
        return input;
    }

    void note(const std::string& message) const {
        if (problem_ && problem_->empty()) *problem_ = message;
    }

    const Stage& stage_;
    double time_;
    std::string* problem_;
};

}  // namespace

std::optional<std::string> directMaterialBinding(const Prim& prim) {
    for (const char* name : {"material:binding:preview", "material:binding"}) {
        auto found = prim.relationships.find(name);
        if (found != prim.relationships.end() && !found->second.targets.empty()) return found->second.targets.front();
    }
    return std::nullopt;
}

const Prim* surfaceShaderOf(const Stage& stage, const Prim& material) {
    const Attribute* surface = material.attribute("outputs:surface");
    if (!surface || surface->connections.empty()) return nullptr;
    return stage.findPrim(splitPropertyPath(surface->connections.front()).first);
}

MaterialPrim readMaterial(const Stage& stage, const Prim& material, double time, std::string* problem) {
    MaterialPrim result;
    result.path = material.path;
    const Attribute* surface = material.attribute("outputs:surface");
    if (!surface || surface->connections.empty()) return result;
    const Prim* shader = stage.findPrim(splitPropertyPath(surface->connections.front()).first);
    if (!shader) {
        if (problem) *problem = material.path + ".outputs:surface connects to " + surface->connections.front() +
                                ", which does not exist";
        return result;
    }
    result.surfaceShaderId = shaderId(*shader, time);
    if (!result.isPreviewSurface()) return result;
    MaterialInputReader reader(stage, time, problem);
    result.diffuseColor = reader.read(*shader, "inputs:diffuseColor", result.diffuseColor);
    result.opacity = reader.read(*shader, "inputs:opacity", result.opacity);
    return result;
}

}  // namespace hdhair::usda
