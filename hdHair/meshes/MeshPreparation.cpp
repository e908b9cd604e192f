// prepareMesh (PreparedMesh.h): check, resolve colours, refine, triangulate
// and move to world space.

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/vec4.hpp>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/meshes/MeshPrimvarResolution.h"
#include "hdHair/meshes/MeshRefinement.h"
#include "hdHair/meshes/PreparedMesh.h"
#include "hdHair/scene/MeshPrim.h"
#include "hdHair/scene/SceneValidation.h"

namespace hdhair {

namespace {

// A face-varying primvar's topology for OpenSubdiv: corners of one vertex
// with equal values share a value (smooth across), different values are a
// seam, whether or not the primvar was indexed. Returns the value index of
// each corner of `topology` and fills `values` with one element per value.
std::vector<int> faceVaryingChannel(const MeshTopology& topology, const ResolvedPrimvar& perCorner,
                                    std::vector<float>& values) {
    const size_t tuple = size_t(perCorner.tupleSize);
    std::map<std::pair<int, std::vector<float>>, int> shared;
    std::vector<int> channel(topology.faceVertexIndices.size());
    for (size_t c = 0; c < channel.size(); ++c) {
        const float* element = perCorner.element(size_t(topology.authoredCorner[c]));
        std::pair<int, std::vector<float>> key(topology.faceVertexIndices[c], std::vector<float>(element, element + tuple));
        auto [found, added] = shared.emplace(std::move(key), int(values.size() / tuple));
        if (added) values.insert(values.end(), element, element + tuple);
        channel[c] = found->second;
    }
    return channel;
}

// Area-weighted smooth normals of a polygon mesh: each vertex sums the
// Newell normals (twice the area along the normal) of the faces around it,
// so faces of no area lend nothing.
std::vector<glm::vec3> faceWeightedNormals(const MeshRefinement& refined) {
    std::vector<glm::dvec3> sums(refined.points().size(), glm::dvec3(0.0));
    size_t corner = 0;
    for (int n : refined.faceVertexCounts()) {
        const int* indices = refined.faceVertexIndices().data() + corner;
        glm::dvec3 normal(0.0);
        for (int i = 0; i < n; ++i) {
            const glm::dvec3 a(refined.points()[size_t(indices[i])]);
            const glm::dvec3 b(refined.points()[size_t(indices[(i + 1) % n])]);
            normal += glm::dvec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
        }
        for (int i = 0; i < n; ++i) sums[size_t(indices[i])] += normal;
        corner += size_t(n);
    }
    std::vector<glm::vec3> normals(sums.size(), glm::vec3(0.0f));
    for (size_t v = 0; v < sums.size(); ++v) {
        const double length = glm::length(sums[v]);
        if (length > 0.0 && std::isfinite(length)) normals[v] = glm::vec3(sums[v] / length);
    }
    return normals;
}

glm::vec3 unitOr(const glm::dvec3& v, const glm::vec3& fallback) {
    const double length = glm::length(v);
    return length > 0.0 && std::isfinite(length) ? glm::vec3(v / length) : fallback;
}

// The displayColor of every refined face corner, in faceVertexIndices() order.
// `faceVaryingValues`: a faceVarying colour's values, refined as channel 0.
std::vector<glm::vec3> cornerColors(const MeshTopology& topology, const MeshRefinement& refined,
                                    const ResolvedPrimvar& color, const std::vector<float>& faceVaryingValues) {
    std::vector<glm::vec3> colors;
    colors.reserve(refined.faceVertexIndices().size());
    auto at = [](const std::vector<float>& values, size_t i) {
        return glm::vec3(values[3 * i], values[3 * i + 1], values[3 * i + 2]);
    };
    size_t corner = 0;
    std::vector<float> perVertex, perCorner;
    if (color.interpolation == Interpolation::Vertex || color.interpolation == Interpolation::Varying)
        perVertex = refined.refineVertexData(color.values, 3, color.interpolation == Interpolation::Varying);
    if (color.interpolation == Interpolation::FaceVarying)
        perCorner = refined.refineFaceVaryingData(0, faceVaryingValues, 3);
    for (size_t f = 0; f < refined.faceVertexCounts().size(); ++f) {
        const int n = refined.faceVertexCounts()[f];
        for (int i = 0; i < n; ++i, ++corner) {
            switch (color.interpolation) {
            case Interpolation::Constant: colors.push_back(at(color.values, 0)); break;
            case Interpolation::Uniform:
                colors.push_back(at(color.values, size_t(topology.authoredFace[size_t(refined.baseFaces()[f])])));
                break;
            case Interpolation::Vertex:
            case Interpolation::Varying:
                colors.push_back(at(perVertex, size_t(refined.faceVertexIndices()[corner])));
                break;
            case Interpolation::FaceVarying: colors.push_back(at(perCorner, corner)); break;
            }
        }
    }
    return colors;
}

}  // namespace

double refinedTriangleCount(const MeshTopology& topology, int level) {
    double triangles = 0.0, corners = 0.0;
    for (size_t f = 0; f < topology.faceCount(); ++f) {
        if (topology.hole[f]) continue;
        triangles += topology.faceVertexCounts[f] - 2;
        corners += topology.faceVertexCounts[f];
    }
    if (level <= 0 || topology.scheme == SubdivisionScheme::None) return triangles;
    // Loop splits each triangle into 4; catmullClark and bilinear split an
    // n-gon into n quads, then each quad into 4 (2 triangles a quad).
    if (topology.scheme == SubdivisionScheme::Loop) return triangles * std::pow(4.0, level);
    return 2.0 * corners * std::pow(4.0, level - 1);
}

int affordableRefineLevel(const MeshTopology& topology, int wanted, size_t maxTriangles) {
    int level = wanted;
    while (level > 0 && refinedTriangleCount(topology, level) > double(maxTriangles)) --level;
    return level;
}

namespace {

// The prim's refine level (or the default), lowered until the refined mesh
// fits kMaxMeshTriangles, with a warning when it had to be.
int refineLevelFor(const MeshPrim& prim, const MeshTopology& topology, int defaultRefineLevel,
                   Diagnostics& diagnostics) {
    int level = prim.refineLevel >= 0 ? prim.refineLevel : defaultRefineLevel;
    level = topology.scheme == SubdivisionScheme::None ? 0 : std::clamp(level, 0, kMaxMeshRefineLevel);
    const int wanted = level;
    level = affordableRefineLevel(topology, wanted, kMaxMeshTriangles);
    if (level < wanted)
        diagnostics.warn(prim.path, fmt::format("refine level {} would make {:.0f} triangles, more than {}; refined "
                                                "to level {} instead",
                                                wanted, refinedTriangleCount(topology, wanted), kMaxMeshTriangles,
                                                level));
    return level;
}

// Meshes are opaque occluders: the opacity is checked like any primvar,
// and a translucent one is said to be drawn opaque.
void checkOpacity(const MeshPrim& prim, const MeshTopology& topology, Diagnostics& diagnostics) {
    const ResolvedPrimvar opacity =
        resolveMeshPrimvar(prim, topology, "displayOpacity", kFallbackDisplayOpacity, diagnostics);
    const auto leastOpacity = std::min_element(opacity.values.begin(), opacity.values.end());
    if (leastOpacity != opacity.values.end() && *leastOpacity < 1.0f)
        diagnostics.warn(prim.path + ".primvars:displayOpacity",
                         fmt::format("opacity down to {}: hdHair draws meshes opaque", *leastOpacity));
}

std::vector<glm::vec3> vertexNormals(const MeshRefinement& refined) {
    std::vector<glm::vec3> normals = faceWeightedNormals(refined);
    if (refined.onLimitSurface()) {
        // The limit normal, where the limit tangents give one.
        for (size_t v = 0; v < normals.size(); ++v)
            if (refined.limitNormals()[v] != glm::vec3(0.0f)) normals[v] = refined.limitNormals()[v];
    }
    return normals;
}

// World space; a mirroring transform turns counter-clockwise faces
// clockwise, so their corners are taken in reverse.
void addWorldTriangles(const glm::dmat4& toWorld, const MeshTopology& topology, const MeshRefinement& refined,
                       const std::vector<glm::vec3>& normals, const std::vector<glm::vec3>& colors,
                       std::vector<MeshVertex>& vertices) {
    const glm::dmat3 normalToWorld = glm::transpose(glm::inverse(glm::dmat3(toWorld)));
    const bool mirrored = glm::determinant(glm::dmat3(toWorld)) < 0.0;
    std::vector<glm::vec3> worldPoints(refined.points().size());
    for (size_t v = 0; v < worldPoints.size(); ++v)
        worldPoints[v] = glm::vec3(toWorld * glm::dvec4(glm::dvec3(refined.points()[v]), 1.0));

    size_t corner = 0;
    for (size_t f = 0; f < refined.faceVertexCounts().size(); ++f) {
        const int n = refined.faceVertexCounts()[f];
        const int* indices = refined.faceVertexIndices().data() + corner;
        const int32_t face = topology.authoredFace[size_t(refined.baseFaces()[f])];
        for (int i = 1; i + 1 < n; ++i) {
            int k[3] = {0, i, i + 1};
            if (mirrored) std::swap(k[1], k[2]);
            const glm::dvec3 a(worldPoints[size_t(indices[k[0]])]), b(worldPoints[size_t(indices[k[1]])]),
                c(worldPoints[size_t(indices[k[2]])]);
            // A vertex without a normal of its own (only faces of no area
            // around it) takes its triangle's; one of no area, any.
            const glm::vec3 triangleNormal = unitOr(glm::cross(b - a, c - a), glm::vec3(0.0f, 0.0f, 1.0f));
            for (int j : k) {
                const size_t vertex = size_t(indices[j]);
                const glm::vec3 objectNormal = normals[vertex];
                MeshVertex out{};
                out.position = worldPoints[vertex];
                out.face = face;
                out.normal = objectNormal == glm::vec3(0.0f)
                                 ? triangleNormal
                                 : unitOr(normalToWorld * glm::dvec3(objectNormal), triangleNormal);
                out.color = colors[corner + size_t(j)];
                vertices.push_back(out);
            }
        }
        corner += size_t(n);
    }
}

void computeBounds(PreparedMesh& prepared) {
    for (const MeshVertex& vertex : prepared.vertices) {
        const bool first = prepared.boundsMin.x > prepared.boundsMax.x;
        prepared.boundsMin = first ? vertex.position : glm::min(prepared.boundsMin, vertex.position);
        prepared.boundsMax = first ? vertex.position : glm::max(prepared.boundsMax, vertex.position);
    }
}

}  // namespace

PreparedMesh prepareMesh(const MeshPrim& prim, int defaultRefineLevel, Diagnostics& diagnostics) {
    PreparedMesh prepared;
    prepared.path = prim.path;
    prepared.authoredFaces = prim.faceVertexCounts.size();
    if (std::string problem = transformProblem(prim.path, prim.worldTransform); !problem.empty()) {
        diagnostics.warn(prim.path, problem);
        return prepared;
    }
    const MeshTopology topology = checkMeshTopology(prim, diagnostics);
    prepared.scheme = topology.scheme;
    const int level = refineLevelFor(prim, topology, defaultRefineLevel, diagnostics);

    const ResolvedPrimvar color =
        resolveMeshPrimvar(prim, topology, "displayColor", kFallbackDisplayColor, diagnostics);
    checkOpacity(prim, topology, diagnostics);

    std::vector<std::vector<int>> channels;
    std::vector<float> faceVaryingValues;
    if (color.interpolation == Interpolation::FaceVarying)
        channels.push_back(faceVaryingChannel(topology, color, faceVaryingValues));
    const MeshRefinement refined(topology, level, channels, prim.path, diagnostics);
    prepared.refineLevel = refined.level();
    const std::vector<glm::vec3> colors = cornerColors(topology, refined, color, faceVaryingValues);
    const std::vector<glm::vec3> normals = vertexNormals(refined);
    addWorldTriangles(prim.worldTransform, topology, refined, normals, colors, prepared.vertices);
    computeBounds(prepared);
    return prepared;
}

}  // namespace hdhair
