#pragma once
// A mesh in the one form the renderer draws: world-space triangles, three
// vertices each, with a smooth unit normal, the resolved displayColor and
// the authored face each triangle belongs to (its elementId). prepareMesh
// checks the topology (MeshTopology), resolves the primvars
// (MeshPrimvarResolution), refines (MeshRefinement) and triangulates;
// hdHair/meshes/README.md has the rules.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "hdHair/meshes/MeshTopology.h"

namespace hdhair {

class Diagnostics;
struct MeshPrim;

// One vertex of the GPU's mesh buffer (shaders/include/meshGeometry.glsl,
// std430): each triangle's three vertices carry the same face.
struct MeshVertex {
    glm::vec3 position;  // world space
    int32_t face;        // the authored face (elementId)
    glm::vec3 normal;    // world space, unit length, on the front side
    float unused0;
    glm::vec3 color;     // linear displayColor
    float unused1;
};
static_assert(sizeof(MeshVertex) == 48, "the std430 layout of MeshVertex");

// The most triangles one mesh may refine to: beyond it the refine level is
// lowered (with a warning), so that no refine level asks for more than
// 144 MB of vertices (48 bytes, 3 a triangle).
constexpr size_t kMaxMeshTriangles = 1'000'000;
// The deepest uniform refinement (Hydra's refine levels go to 8).
constexpr int kMaxMeshRefineLevel = 8;

struct PreparedMesh {
    std::string path;
    std::vector<MeshVertex> vertices;  // 3 per triangle, counter-clockwise seen from the front
    glm::vec3 boundsMin{1.0f}, boundsMax{-1.0f};  // world space; min > max when empty
    SubdivisionScheme scheme = SubdivisionScheme::CatmullClark;  // as drawn
    int refineLevel = 0;  // the level drawn (0: the cage, or polygons for scheme none)
    size_t authoredFaces = 0;

    size_t triangleCount() const { return vertices.size() / 3; }
    bool empty() const { return vertices.empty(); }
};

// How many triangles `topology` refines to at `level`.
double refinedTriangleCount(const MeshTopology& topology, int level);
// The highest level up to `wanted` at which `topology` makes at most
// `maxTriangles` triangles (0 when even the cage makes more).
int affordableRefineLevel(const MeshTopology& topology, int wanted, size_t maxTriangles);

// `defaultRefineLevel` applies where the prim has no level of its own
// (MeshPrim::refineLevel < 0): the meshRefineLevel setting. Repairs are
// reported to `diagnostics`; never throws for bad input.
PreparedMesh prepareMesh(const MeshPrim& prim, int defaultRefineLevel, Diagnostics& diagnostics);

}  // namespace hdhair
