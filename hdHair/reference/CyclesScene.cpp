#include "hdHair/reference/CyclesScene.h"

#include <fstream>
#include <stdexcept>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/curves/StrandColorSource.h"
#include "hdHair/meshes/PreparedMesh.h"
#include "hdHair/plan/CameraView.h"
#include "hdHair/plan/RenderPlan.h"
#include "hdHair/plan/RenderSettings.h"
#include "hdHair/scene/Scene.h"

namespace hdhair {
namespace {

nlohmann::json rows(const glm::dmat4& m) {
    nlohmann::json result = nlohmann::json::array();
    for (int row = 0; row < 4; ++row) result.push_back({m[0][row], m[1][row], m[2][row], m[3][row]});
    return result;
}

nlohmann::json rows(const glm::dmat3& m) {
    nlohmann::json result = nlohmann::json::array();
    for (int row = 0; row < 3; ++row) result.push_back({m[0][row], m[1][row], m[2][row]});
    return result;
}

nlohmann::json rgb(const glm::vec3& v) { return {v.r, v.g, v.b}; }

const char* toString(CyclesLight::Kind kind) {
    switch (kind) {
        case CyclesLight::Kind::Sun: return "sun";
        case CyclesLight::Kind::Point: return "point";
        case CyclesLight::Kind::Spot: return "spot";
        case CyclesLight::Kind::Area: return "area";
    }
    return "?";
}

// Appends arrays to scene.bin's bytes and says where each went.
class BlobWriter {
public:
    template <typename T>
    nlohmann::json add(const std::vector<T>& values) {
        static_assert(sizeof(T) == 4, "float32 and int32 only");
        nlohmann::json where = {{"offset", bytes_.size()}, {"count", values.size()}};
        const char* data = reinterpret_cast<const char*>(values.data());
        bytes_.insert(bytes_.end(), data, data + values.size() * sizeof(T));
        return where;
    }
    const std::vector<char>& bytes() const { return bytes_; }

private:
    std::vector<char> bytes_;
};

bool stageHasLight(const Scene& scene) {
    for (const auto& [path, entry] : scene.lights())
        if (entry.prim->visible && !entry.prim->hostCameraLight) return true;
    return false;
}

nlohmann::json describe(const CyclesScene& scene, BlobWriter* blob) {
    nlohmann::json json;
    json["format"] = "hdhair-cycles-scene";
    json["version"] = 1;
    const CyclesCamera& camera = scene.camera;
    json["camera"] = {{"type", camera.orthographic ? "ORTHO" : "PERSP"},
                      {"cameraToWorld", rows(camera.cameraToWorld)},
                      {"angleX", camera.angleX},
                      {"orthoScale", camera.orthoScale},
                      {"shiftX", camera.shiftX},
                      {"shiftY", camera.shiftY},
                      {"clipStart", camera.clipStart},
                      {"clipEnd", camera.clipEnd},
                      {"width", camera.width},
                      {"height", camera.height}};
    const CyclesRenderOptions& options = scene.options;
    json["render"] = {{"samples", options.samples},
                      {"seed", options.seed},
                      {"maxBounces", options.maxBounces},
                      {"timeLimit", options.timeLimitSeconds},
                      {"threads", options.threads}};
    json["lights"] = nlohmann::json::array();
    for (const CyclesLight& light : scene.lighting.lights)
        json["lights"].push_back({{"path", light.path},
                                  {"kind", toString(light.kind)},
                                  {"lightToWorld", rows(light.lightToWorld)},
                                  {"strength", rgb(light.strength)},
                                  {"radius", light.radius},
                                  {"angle", light.angle},
                                  {"disk", light.disk},
                                  {"sizeX", light.sizeX},
                                  {"sizeY", light.sizeY},
                                  {"spotSize", light.spotSize},
                                  {"spotBlend", light.spotBlend},
                                  {"castShadow", light.castShadow}});
    json["domes"] = nlohmann::json::array();
    for (const CyclesDome& dome : scene.lighting.domes)
        json["domes"].push_back({{"path", dome.path},
                                 {"radiance", rgb(dome.radiance)},
                                 {"texture", dome.textureFile},
                                 {"worldToTexture", rows(dome.worldToTexture)}});
    json["curves"] = nlohmann::json::array();
    for (const CyclesStrands& strands : scene.strands) {
        nlohmann::json prim = {{"path", strands.path},
                               {"flat", strands.flat},
                               {"curveCount", strands.keysPerCurve.size()},
                               {"keyCount", strands.keyCount()}};
        if (!strands.flat)
            prim["hair"] = {{"absorption", rgb(strands.hair.absorption)},
                            {"roughness", strands.hair.roughness},
                            {"radialRoughness", strands.hair.radialRoughness},
                            {"ior", strands.hair.ior},
                            {"offset", strands.hair.offset},
                            {"coat", strands.hair.coat},
                            {"absorptionPerKey", strands.absorptionPerPoint}};
        if (blob) {
            prim["keysPerCurve"] = blob->add(strands.keysPerCurve);
            prim["positions"] = blob->add(strands.positions);
            prim["radii"] = blob->add(strands.radii);
            prim["colors"] = blob->add(strands.colors);
            prim["opacities"] = blob->add(strands.opacities);
            if (strands.absorptionPerPoint) prim["absorption"] = blob->add(strands.absorption);
        }
        json["curves"].push_back(prim);
    }
    json["meshes"] = nlohmann::json::array();
    for (const CyclesMeshExport& mesh : scene.meshes) {
        nlohmann::json prim = {{"path", mesh.path}, {"triangleCount", mesh.positions.size() / 9}};
        if (blob) {
            prim["positions"] = blob->add(mesh.positions);
            prim["normals"] = blob->add(mesh.normals);
            prim["colors"] = blob->add(mesh.colors);
        }
        json["meshes"].push_back(prim);
    }
    return json;
}

}  // namespace

CyclesScene exportCyclesScene(const Scene& scene, const CyclesFraming& framing, const RenderSettings& settings,
                              const CyclesRenderOptions& options, Diagnostics& diagnostics, CameraView* view) {
    CyclesScene result;
    result.options = options;
    const RenderingSpace space = settings.renderingSpace();
    std::vector<FramingPoints> framingPoints;
    bool anyLit = false;
    for (const auto& [path, entry] : scene.curves()) {
        const CurvesPrim& prim = *entry.prim;
        if (!prim.visible) continue;
        const SceneEntry<MaterialPrim>* material = scene.findMaterial(prim.materialBinding);
        const StrandColorSource colors = strandColorSource(prim, material ? material->prim.get() : nullptr,
                                                           diagnostics);
        PreparedCurves prepared = prepareCurves(prim, diagnostics, hairParameterPrimvars(), &colors);
        if (prepared.empty()) continue;
        // As the renderer does: authored colours are linear Rec.709 and
        // shading (absorption from colour included) happens in the rendering space.
        if (space != RenderingSpace::LinearRec709)
            for (StrandControlPoint& point : prepared.controlPoints) point.color = toRenderingSpace(space, point.color);
        const HairMaterial hair = hairMaterialFor(prim, prepared, settings, diagnostics);
        if (hair.model == ShadingModel::KajiyaKay)
            diagnostics.warn(prim.path, "Kajiya-Kay has no physical counterpart: the reference shades these "
                                        "strands with Principled Hair, its absorption from their colour");
        if (hair.model == ShadingModel::Marschner && (hair.varies & (kEtaVaries | kLongitudinalVaries)) != 0)
            diagnostics.warn(prim.path, "hdHair:eta, longitudinalShift or longitudinalWidth vary over the prim: the "
                                        "reference gives every strand their mean (only absorption varies per key)");
        anyLit = anyLit || hair.model != ShadingModel::Flat;
        if (!framing.camera) framingPoints.push_back(spanFramingPoints(prepared));
        result.strands.push_back(cyclesStrands(prepared, hair, options.pointsPerSpan));
        result.curves += result.strands.back().keysPerCurve.size();
        result.keys += result.strands.back().keyCount();
    }
    const bool meshesLit = settings.values().shadingModel != ShadingModel::Flat;
    for (const auto& [path, entry] : scene.meshes()) {
        if (!entry.prim->visible) continue;
        if (!framing.camera) framingPoints.push_back(meshFramingPoints(*entry.prim));
        const PreparedMesh prepared = prepareMesh(*entry.prim, settings.values().meshRefineLevel, diagnostics);
        if (prepared.empty()) continue;
        if (!meshesLit)
            diagnostics.warn(path, "shadingModel=flat draws meshes unlit; the reference lights them (diffuse)");
        anyLit = true;
        CyclesMeshExport mesh;
        mesh.path = path;
        for (const MeshVertex& vertex : prepared.vertices) {
            const glm::vec3 color = toRenderingSpace(space, vertex.color);
            mesh.positions.insert(mesh.positions.end(), {vertex.position.x, vertex.position.y, vertex.position.z});
            mesh.normals.insert(mesh.normals.end(), {vertex.normal.x, vertex.normal.y, vertex.normal.z});
            mesh.colors.insert(mesh.colors.end(), {color.r, color.g, color.b});
        }
        result.triangles += prepared.triangleCount();
        result.meshes.push_back(std::move(mesh));
    }
    const CameraView camera = framing.camera ? *framing.camera : framing.frame(framingBounds(framingPoints, diagnostics));
    if (view) *view = camera;
    result.camera = cyclesCamera(camera);
    const bool cameraLight = usesCameraLight(settings.values().cameraLight, stageHasLight(scene), anyLit);
    result.lighting = cyclesLighting(scene, camera, cameraLight, settings.values().cameraLightShadows == CameraLightShadows::On, space,
                                     diagnostics);
    return result;
}

nlohmann::json describeCyclesScene(const CyclesScene& scene) { return describe(scene, nullptr); }

void writeCyclesScene(const CyclesScene& scene, const std::filesystem::path& folder) {
    BlobWriter blob;
    const nlohmann::json json = describe(scene, &blob);
    auto write = [](const std::filesystem::path& path, const char* data, size_t size) {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(data, std::streamsize(size));
        out.close();
        if (!out) throw std::runtime_error("cannot write '" + path.string() + "'");
    };
    const std::string text = json.dump(1);
    write(folder / "scene.json", text.data(), text.size());
    write(folder / "scene.bin", blob.bytes().data(), blob.bytes().size());
}

}  // namespace hdhair
