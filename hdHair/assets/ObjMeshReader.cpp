#include "hdHair/assets/ObjMeshReader.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>
#include <tiny_obj_loader.h>

namespace hdhair::convert {

PolygonMesh readObjMesh(const std::string& path) {
    tinyobj::ObjReaderConfig config;
    config.triangulate = false;  // faces as authored
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(path, config)) {
        std::string error = reader.Error();
        while (!error.empty() && error.back() == '\n') error.pop_back();
        throw std::invalid_argument(fmt::format("{}: {}", path, error.empty() ? "cannot read the file" : error));
    }
    PolygonMesh mesh;
    mesh.source = path;
    std::istringstream warnings(reader.Warning());
    for (std::string line; std::getline(warnings, line);)
        if (!line.empty()) mesh.warnings.push_back(line);

    const std::vector<tinyobj::real_t>& vertices = reader.GetAttrib().vertices;
    mesh.points.reserve(vertices.size() / 3);
    for (size_t v = 0; v + 2 < vertices.size(); v += 3) {
        const Float3 p{float(vertices[v]), float(vertices[v + 1]), float(vertices[v + 2])};
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw std::invalid_argument(fmt::format("{}: vertex {} is not finite", path, v / 3 + 1));
        mesh.points.push_back(p);
    }
    for (const tinyobj::shape_t& shape : reader.GetShapes()) {
        size_t corner = 0;
        for (unsigned char count : shape.mesh.num_face_vertices) {
            mesh.faceVertexCounts.push_back(int(count));
            for (size_t k = 0; k < count; ++k, ++corner) {
                const int index = shape.mesh.indices.at(corner).vertex_index;
                if (index < 0 || size_t(index) >= mesh.points.size())
                    throw std::invalid_argument(fmt::format("{}: face {} of '{}' names vertex {}, outside the {} "
                                                            "vertices",
                                                            path, mesh.faceVertexCounts.size(), shape.name, index + 1,
                                                            mesh.points.size()));
                mesh.faceVertexIndices.push_back(index);
            }
        }
    }
    if (mesh.faceVertexCounts.empty()) throw std::invalid_argument(fmt::format("{}: no faces", path));
    return mesh;
}

}  // namespace hdhair::convert
