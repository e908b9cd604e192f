// MeshRefinement against values worked out by hand from the subdivision
// rules: Catmull-Clark's and Loop's limit masks, sharp creases, holes.

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "TestMeshes.h"
#include "hdHair/base/Diagnostics.h"
#include "hdHair/meshes/MeshRefinement.h"
#include "hdHair/meshes/MeshTopology.h"

using namespace hdhair;
using hdhair::test::cube;
using hdhair::test::octahedron;
using hdhair::test::quadGrid;
using hdhair::test::warningsText;

namespace {

MeshTopology topologyOf(const MeshPrim& mesh) {
    Diagnostics diagnostics;
    MeshTopology topology = checkMeshTopology(mesh, diagnostics);
    EXPECT_EQ(diagnostics.warningCount(), 0u) << warningsText(diagnostics);
    return topology;
}

// `topology` refined to `level`, with no warning.
std::unique_ptr<MeshRefinement> refine(const MeshTopology& topology, int level,
                                       const std::vector<std::vector<int>>& channels = {}) {
    Diagnostics diagnostics;
    auto refined = std::make_unique<MeshRefinement>(topology, level, channels, "/mesh", diagnostics);
    EXPECT_EQ(diagnostics.warningCount(), 0u) << warningsText(diagnostics);
    return refined;
}

// The refined point nearest `target`.
glm::vec3 nearestPoint(const MeshRefinement& refined, const glm::vec3& target) {
    return *std::min_element(refined.points().begin(), refined.points().end(),
                             [&](const glm::vec3& a, const glm::vec3& b) {
                                 return glm::length(a - target) < glm::length(b - target);
                             });
}

}  // namespace

// Catmull-Clark's limit of a vertex of valence n is its limit mask
// (n^2 v + 4 sum e_i + sum f_i) / (n (n + 5)) over its edge neighbours e_i
// and diagonal neighbours f_i. The corner (1, 1, 1): n = 3, the e_i's x sum
// to 1 and the f_i's to -1, so x = (9 + 4 - 1) / 24 = 1/2. The centre of the
// face x = 1 after one step: n = 4, v = (1, 0, 0), its edge points (3/4,
// +-3/4, 0) and (3/4, 0, +-3/4), its diagonal corners' vertex points at
// x = 5/9: x = (16 + 4 * 3 + 4 * 5/9) / 36 = 68/81. A vertex's limit does
// not change with the level.
TEST(MeshRefinement, CatmullClarkCubeLiesOnItsLimitAtEveryLevel) {
    const MeshTopology topology = topologyOf(cube());
    for (int level = 1; level <= 3; ++level) {
        const auto refined = refine(topology, level);
        EXPECT_EQ(refined->level(), level);
        EXPECT_TRUE(refined->onLimitSurface());
        EXPECT_EQ(refined->faceVertexCounts().size(), 6u * 4u << (2 * (level - 1)));
        const glm::vec3 corner = nearestPoint(*refined, glm::vec3(1.0f));
        EXPECT_NEAR(corner.x, 0.5f, 1e-6f) << "level " << level;
        EXPECT_NEAR(corner.y, 0.5f, 1e-6f);
        const glm::vec3 faceCentre = nearestPoint(*refined, glm::vec3(1.0f, 0.0f, 0.0f));
        EXPECT_NEAR(faceCentre.x, 68.0f / 81.0f, 1e-6f) << "level " << level;
        EXPECT_NEAR(faceCentre.y, 0.0f, 1e-6f);
        // Sphere-like: every point between the face centres' and the corners' radii.
        for (const glm::vec3& p : refined->points()) {
            EXPECT_GE(glm::length(p), 68.0f / 81.0f - 1e-5f);
            EXPECT_LE(glm::length(p), std::sqrt(0.75f) + 1e-5f);
        }
        // Limit normals point out of the surface.
        ASSERT_EQ(refined->limitNormals().size(), refined->points().size());
        for (size_t v = 0; v < refined->points().size(); ++v) {
            EXPECT_NEAR(glm::length(refined->limitNormals()[v]), 1.0f, 1e-5f);
            EXPECT_GT(glm::dot(refined->limitNormals()[v], glm::normalize(refined->points()[v])), 0.8f);
        }
    }
}

// With every edge infinitely sharp (sharpness 10 and more), the limit
// surface is the cube itself: every point stays on a face of [-1, 1]^3.
TEST(MeshRefinement, SharpCreasesKeepTheCubesEdges) {
    MeshPrim mesh = cube();
    const std::vector<int> edges = {0, 1, 1, 3, 3, 2, 2, 0, 4, 5, 5, 7, 7, 6, 6, 4, 0, 4, 1, 5, 2, 6, 3, 7};
    for (size_t e = 0; e < edges.size(); e += 2) {
        mesh.creaseIndices.insert(mesh.creaseIndices.end(), {edges[e], edges[e + 1]});
        mesh.creaseLengths.push_back(2);
        mesh.creaseSharpnesses.push_back(10.0f);
    }
    const MeshTopology topology = topologyOf(mesh);
    const auto refined = refine(topology, 3);
    for (const glm::vec3& p : refined->points())
        EXPECT_NEAR(std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}), 1.0f, 1e-5f);
    EXPECT_NEAR(nearestPoint(*refined, glm::vec3(1.0f)).x, 1.0f, 1e-6f);  // the corner stays a corner

    // One semi-sharp crease (sharpness 1) pulls its edge out less than an
    // infinitely sharp one and more than none.
    auto edgeMiddle = [&](float sharpness) {
        MeshPrim one = cube();
        one.creaseIndices = {3, 7};
        one.creaseLengths = {2};
        one.creaseSharpnesses = {sharpness};
        return glm::length(nearestPoint(*refine(topologyOf(one), 3), glm::vec3(1.0f, 1.0f, 0.0f)));
    };
    EXPECT_LT(edgeMiddle(0.0f), edgeMiddle(1.0f));
    EXPECT_LT(edgeMiddle(1.0f), edgeMiddle(10.0f));
}

TEST(MeshRefinement, HolesLeaveNoRefinedFace) {
    MeshPrim mesh = cube();
    mesh.holeIndices = {1};
    const MeshTopology topology = topologyOf(mesh);
    const auto refined = refine(topology, 2);
    EXPECT_EQ(refined->faceVertexCounts().size(), 5u * 16u);
    for (int base : refined->baseFaces()) EXPECT_NE(base, 1);
    EXPECT_EQ(std::count(refined->baseFaces().begin(), refined->baseFaces().end(), 0), 16);
}

// Loop's limit mask for valence 4 (OpenSubdiv's and Loop's): edge weight
// 1 / (n + 3 / (8 gamma)) with gamma = (5/8 - (3/8 + cos(2 pi / n) / 4)^2) / n
// = 31/256, so 31/220 per neighbour and 96/220 = 24/55 for the vertex. The
// octahedron's neighbours of (1, 0, 0) sum to zero: its limit is (24/55, 0, 0).
TEST(MeshRefinement, LoopOctahedronLiesOnItsLimit) {
    const MeshTopology topology = topologyOf(octahedron());
    const auto refined = refine(topology, 2);
    EXPECT_EQ(refined->faceVertexCounts(), std::vector<int>(8 * 16, 3));
    const glm::vec3 tip = nearestPoint(*refined, glm::vec3(1.0f, 0.0f, 0.0f));
    EXPECT_NEAR(tip.x, 24.0f / 55.0f, 1e-6f);
    EXPECT_NEAR(tip.y, 0.0f, 1e-6f);
    for (size_t v = 0; v < refined->points().size(); ++v)
        EXPECT_GT(glm::dot(refined->limitNormals()[v], glm::normalize(refined->points()[v])), 0.8f);
}

TEST(MeshRefinement, LevelZeroAndSchemeNoneAreTheCage) {
    MeshPrim mesh = cube();
    mesh.holeIndices = {2};
    const MeshTopology topology = topologyOf(mesh);
    const auto cage = refine(topology, 0);
    EXPECT_FALSE(cage->onLimitSurface());
    EXPECT_EQ(cage->points(), topology.points);
    EXPECT_EQ(cage->baseFaces(), (std::vector<int>{0, 1, 3, 4, 5}));
    mesh.subdivisionScheme = "none";
    const auto polygons = refine(topologyOf(mesh), 3);
    EXPECT_EQ(polygons->level(), 0);
    EXPECT_EQ(polygons->faceVertexCounts().size(), 5u);
}

// Face-varying data: one value per face on every corner of the face (seams
// at every edge) stays that face's value on every refined corner.
TEST(MeshRefinement, FaceVaryingSeamsKeepEachFacesValue) {
    const MeshTopology topology = topologyOf(cube());
    std::vector<int> channel(24);
    for (int c = 0; c < 24; ++c) channel[size_t(c)] = c / 4;  // face f's corners share value f
    const std::vector<float> values = {0.0f, 1.0f, 2.0f, 3.0f, 4.0f, 5.0f};
    const auto refined = refine(topology, 2, {channel});
    const std::vector<float> corners = refined->refineFaceVaryingData(0, values, 1);
    ASSERT_EQ(corners.size(), refined->faceVertexIndices().size());
    size_t corner = 0;
    for (size_t f = 0; f < refined->faceVertexCounts().size(); ++f)
        for (int i = 0; i < refined->faceVertexCounts()[f]; ++i, ++corner)
            EXPECT_NEAR(corners[corner], float(refined->baseFaces()[f]), 1e-6f);
    // Vertex data goes through the same masks as the points: the x
    // coordinates as data land where the points do.
    std::vector<float> xs;
    for (const glm::vec3& p : topology.points) xs.push_back(p.x);
    const std::vector<float> refinedXs = refined->refineVertexData(xs, 1, false);
    for (size_t v = 0; v < refined->points().size(); ++v) EXPECT_NEAR(refinedXs[v], refined->points()[v].x, 1e-6f);
}

TEST(MeshRefinement, BilinearSplitsFacesWithoutMovingThem) {
    MeshPrim mesh = quadGrid(1);
    mesh.subdivisionScheme = "bilinear";
    const auto refined = refine(topologyOf(mesh), 2);
    EXPECT_FALSE(refined->onLimitSurface());
    EXPECT_EQ(refined->faceVertexCounts().size(), 16u);
    for (const glm::vec3& p : refined->points()) {
        EXPECT_EQ(p.z, 0.0f);
        EXPECT_EQ(p.x * 4.0f, std::round(p.x * 4.0f));  // on the quarter grid
    }
}
