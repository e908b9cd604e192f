#pragma once
// Meshes built in code for the mesh tests, each with values worked out by
// hand in the tests that use them.

#include <cmath>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/scene/MeshPrim.h"

namespace hdhair::test {

// The cube [-1, 1]^3: 8 points, 6 quads wound counter-clockwise seen from
// outside (right-handed). Faces: 0 -z, 1 +z, 2 -y, 3 +y, 4 -x, 5 +x.
inline MeshPrim cube(const std::string& path = "/cube") {
    MeshPrim mesh;
    mesh.path = path;
    for (int i = 0; i < 8; ++i)
        mesh.points.emplace_back((i & 1) ? 1.0f : -1.0f, (i & 2) ? 1.0f : -1.0f, (i & 4) ? 1.0f : -1.0f);
    mesh.faceVertexCounts = {4, 4, 4, 4, 4, 4};
    mesh.faceVertexIndices = {0, 2, 3, 1,   // -z
                              4, 5, 7, 6,   // +z
                              0, 1, 5, 4,   // -y
                              2, 6, 7, 3,   // +y
                              0, 4, 6, 2,   // -x
                              1, 3, 7, 5};  // +x
    return mesh;
}

// The octahedron with vertices at +-1 on each axis: 8 triangles, right-handed.
inline MeshPrim octahedron(const std::string& path = "/octahedron") {
    MeshPrim mesh;
    mesh.path = path;
    mesh.subdivisionScheme = "loop";
    mesh.points = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    mesh.faceVertexCounts = std::vector<int>(8, 3);
    mesh.faceVertexIndices = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
    return mesh;
}

// An n x n grid of unit quads in the z = 0 plane, facing +z, from (0, 0) to
// (n, n); face f is at column f % n, row f / n.
inline MeshPrim quadGrid(int n, const std::string& path = "/grid") {
    MeshPrim mesh;
    mesh.path = path;
    mesh.subdivisionScheme = "none";
    for (int y = 0; y <= n; ++y)
        for (int x = 0; x <= n; ++x) mesh.points.emplace_back(float(x), float(y), 0.0f);
    for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
            const int a = y * (n + 1) + x;
            mesh.faceVertexCounts.push_back(4);
            mesh.faceVertexIndices.insert(mesh.faceVertexIndices.end(), {a, a + 1, a + n + 2, a + n + 1});
        }
    }
    return mesh;
}

// A UV sphere of `radius` about `centre`, its poles on the z axis, `rings`
// bands of `segments` faces (triangles at the poles, quads between),
// right-handed, scheme none: drawn as these polygons.
inline MeshPrim uvSphere(const std::string& path, glm::vec3 centre, float radius, int rings = 16, int segments = 32) {
    MeshPrim mesh;
    mesh.path = path;
    mesh.subdivisionScheme = "none";
    const double pi = 3.14159265358979323846;
    mesh.points.push_back(centre + glm::vec3(0.0f, 0.0f, radius));  // 0: the +z pole
    for (int r = 1; r < rings; ++r) {
        const double theta = pi * r / rings;
        for (int s = 0; s < segments; ++s) {
            const double phi = 2.0 * pi * s / segments;
            mesh.points.push_back(centre + radius * glm::vec3(float(std::sin(theta) * std::cos(phi)),
                                                              float(std::sin(theta) * std::sin(phi)),
                                                              float(std::cos(theta))));
        }
    }
    const int south = int(mesh.points.size());
    mesh.points.push_back(centre - glm::vec3(0.0f, 0.0f, radius));
    auto ring = [&](int r, int s) { return 1 + (r - 1) * segments + (s % segments); };
    for (int s = 0; s < segments; ++s) {
        mesh.faceVertexCounts.push_back(3);
        mesh.faceVertexIndices.insert(mesh.faceVertexIndices.end(), {0, ring(1, s), ring(1, s + 1)});
    }
    for (int r = 1; r + 1 < rings; ++r) {
        for (int s = 0; s < segments; ++s) {
            mesh.faceVertexCounts.push_back(4);
            mesh.faceVertexIndices.insert(mesh.faceVertexIndices.end(),
                                          {ring(r, s), ring(r + 1, s), ring(r + 1, s + 1), ring(r, s + 1)});
        }
    }
    for (int s = 0; s < segments; ++s) {
        mesh.faceVertexCounts.push_back(3);
        mesh.faceVertexIndices.insert(mesh.faceVertexIndices.end(), {south, ring(rings - 1, s + 1), ring(rings - 1, s)});
    }
    return mesh;
}

inline std::string warningsText(const Diagnostics& diagnostics) {
    std::string text;
    for (const Diagnostic& d : diagnostics.warnings()) text += d.where + ": " + d.message + "\n";
    return text;
}

}  // namespace hdhair::test
