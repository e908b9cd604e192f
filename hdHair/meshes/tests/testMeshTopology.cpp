// checkMeshTopology: what is kept, how it maps back to the authored faces and
// corners, and every repair with its one warning.

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "TestMeshes.h"
#include "hdHair/base/Diagnostics.h"
#include "hdHair/meshes/MeshTopology.h"

using namespace hdhair;
using hdhair::test::cube;
using hdhair::test::quadGrid;
using hdhair::test::warningsText;

namespace {

// What checkMeshTopology makes of `mesh`, and its warnings, one a line.
struct Checked {
    MeshTopology topology;
    std::string warnings;
};

Checked check(const MeshPrim& mesh) {
    Diagnostics diagnostics;
    MeshTopology topology = checkMeshTopology(mesh, diagnostics);
    return {std::move(topology), warningsText(diagnostics)};
}

}  // namespace

TEST(MeshTopology, AValidMeshKeepsEveryFaceAndCornerInOrder) {
    const auto [topology, warnings] = check(cube());
    EXPECT_EQ(warnings, "");
    EXPECT_EQ(topology.scheme, SubdivisionScheme::CatmullClark);
    EXPECT_EQ(topology.faceVertexCounts, cube().faceVertexCounts);
    EXPECT_EQ(topology.faceVertexIndices, cube().faceVertexIndices);
    EXPECT_EQ(topology.authoredFace, (std::vector<int>{0, 1, 2, 3, 4, 5}));
    ASSERT_EQ(topology.authoredCorner.size(), 24u);
    for (size_t c = 0; c < 24; ++c) EXPECT_EQ(topology.authoredCorner[c], int(c));
    EXPECT_EQ(topology.authoredFaceCount, 6u);
    EXPECT_EQ(topology.authoredPointCount, 8u);
    EXPECT_EQ(topology.authoredCornerCount, 24u);
}

TEST(MeshTopology, LeftHandedFacesAreReversedKeepingTheirFirstCorner) {
    MeshPrim mesh = quadGrid(1);
    mesh.orientation = "leftHanded";
    mesh.faceVertexIndices = {0, 2, 3, 1};  // clockwise seen from +z: leftHanded, its front is +z
    const auto [topology, warnings] = check(mesh);
    EXPECT_EQ(warnings, "");
    EXPECT_EQ(topology.faceVertexIndices, (std::vector<int>{0, 1, 3, 2}));
    EXPECT_EQ(topology.authoredCorner, (std::vector<int>{0, 3, 2, 1}));
}

TEST(MeshTopology, BadFacesAreLeftOutAndTheRestKeepTheirAuthoredNumbers) {
    MeshPrim mesh = quadGrid(2);  // 9 points, 4 quads
    mesh.faceVertexCounts = {4, 2, -1, 4, 4, 4};
    mesh.faceVertexIndices = {0, 1, 4, 3,  // face 0: kept
                              1, 2,        // face 1: two vertices
                                           // face 2: negative count, takes no index
                              1, 2, 5, 99, // face 3: a point that does not exist
                              3, 4, 7, 6,  // face 4: kept
                              4, 5};       // face 5: runs past the end
    const auto [topology, warnings] = check(mesh);
    EXPECT_EQ(topology.authoredFace, (std::vector<int>{0, 4}));
    EXPECT_EQ(topology.faceVertexIndices, (std::vector<int>{0, 1, 4, 3, 3, 4, 7, 6}));
    EXPECT_EQ(topology.authoredCorner, (std::vector<int>{0, 1, 2, 3, 10, 11, 12, 13}));
    EXPECT_EQ(warnings,
              "/grid.faceVertexCounts: 1 face has a negative vertex count (first: face 2); not drawn\n"
              "/grid.faceVertexCounts: 1 face has fewer than 3 vertices (first: face 1); not drawn\n"
              "/grid.faceVertexCounts: the faces need 18 faceVertexIndices, found 16; the last 1 face is (from "
              "face 5) not drawn\n"
              "/grid.faceVertexIndices: 1 face names a point outside the 9 points (first: face 3); not drawn\n");
}

TEST(MeshTopology, ExtraIndicesAreIgnoredWithAWarning) {
    MeshPrim mesh = quadGrid(1);
    mesh.faceVertexIndices.push_back(0);
    const auto [topology, warnings] = check(mesh);
    EXPECT_EQ(topology.faceCount(), 1u);
    EXPECT_EQ(warnings,
              "/grid.faceVertexIndices: 5 indices, 1 more than the faces use; the rest are ignored\n");
}

TEST(MeshTopology, AHugeDeclaredFaceSizeIsRejectedWithoutAllocating) {
    MeshPrim mesh = quadGrid(1);
    mesh.faceVertexCounts = {std::numeric_limits<int>::max(), 4};
    const auto [topology, warnings] = check(mesh);
    EXPECT_EQ(topology.faceCount(), 0u);
    EXPECT_EQ(warnings, "/grid.faceVertexCounts: the faces need 2147483651 faceVertexIndices, "
                                         "found 4; the last 2 faces are (from face 0) not drawn\n");
}

TEST(MeshTopology, HolesNameAuthoredFaces) {
    MeshPrim mesh = quadGrid(2);
    mesh.faceVertexCounts = {4, 2, 4, 4};  // face 1 is left out, so kept face 1 is authored face 2
    mesh.faceVertexIndices = {0, 1, 4, 3, 1, 2, 3, 4, 7, 6, 4, 5, 8, 7};
    mesh.holeIndices = {2, 1, 7, -1};
    const auto [topology, warnings] = check(mesh);
    EXPECT_EQ(topology.authoredFace, (std::vector<int>{0, 2, 3}));
    EXPECT_EQ(topology.hole, (std::vector<bool>{false, true, false}));
    EXPECT_NE(warnings.find("/grid.holeIndices: 2 holes are outside the 4 faces (first: "
                                             "holeIndices[2]); ignored\n"),
              std::string::npos)
        << warnings;
}

TEST(MeshTopology, NonFinitePointsBecomeTheirNeighboursMeanAndTheirFacesHoles) {
    MeshPrim mesh = quadGrid(2);
    mesh.points[4] = glm::vec3(std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f);  // the centre, in every face
    mesh.points[8] = glm::vec3(0.0f, std::numeric_limits<float>::infinity(), 0.0f);   // a corner, in face 3
    mesh.faceVertexCounts.push_back(4);  // a fifth face away from both
    mesh.points.insert(mesh.points.end(), {{5, 0, 0}, {6, 0, 0}, {6, 1, 0}, {5, 1, 0}});
    mesh.faceVertexIndices.insert(mesh.faceVertexIndices.end(), {9, 10, 11, 12});
    const auto [topology, warnings] = check(mesh);
    EXPECT_EQ(topology.hole, (std::vector<bool>{true, true, true, true, false}));
    // The centre's finite neighbours in its four faces, counted once per
    // face: (0,0) (1,0) (0,1) | (1,0) (2,0) (2,1) | (0,1) (1,2) (0,2) |
    // (2,1) (1,2): 11 points summing to (10, 10).
    const glm::vec3 centre = topology.points[4];
    const glm::vec3 expected(10.0f / 11.0f, 10.0f / 11.0f, 0.0f);
    EXPECT_NEAR(centre.x, expected.x, 1e-6f);
    EXPECT_NEAR(centre.y, expected.y, 1e-6f);
    EXPECT_EQ(warnings,
              "/grid.points: 2 points are not finite (first: points[4]); the faces using them are not drawn\n");
}

TEST(MeshTopology, ZeroAreaFacesAreKeptAndReported) {
    MeshPrim mesh = quadGrid(1);
    mesh.points.insert(mesh.points.end(), {{3, 0, 0}, {4, 0, 0}, {5, 0, 0}});  // collinear
    mesh.faceVertexCounts = {4, 3, 3};
    mesh.faceVertexIndices = {0, 1, 3, 2, 4, 5, 6, 0, 0, 1};  // a line and a repeated point
    const auto [topology, warnings] = check(mesh);
    EXPECT_EQ(topology.faceCount(), 3u);
    EXPECT_EQ(warnings,
              "/grid.faceVertexCounts: 2 faces have no area (first: face 1); they cover no pixels and no normal\n");
}

TEST(MeshTopology, CreaseChainsBecomeEdgesWithSharpnessPerCreaseOrPerEdge) {
    MeshPrim mesh = cube();
    mesh.creaseIndices = {0, 2, 3, 4, 5};
    mesh.creaseLengths = {3, 2};
    mesh.creaseSharpnesses = {2.0f, 5.0f};  // per crease
    Checked checked = check(mesh);
    EXPECT_EQ(checked.warnings, "");
    EXPECT_EQ(checked.topology.creaseEdges, (std::vector<int>{0, 2, 2, 3, 4, 5}));
    EXPECT_EQ(checked.topology.creaseSharpnesses, (std::vector<float>{2.0f, 2.0f, 5.0f}));

    mesh.creaseSharpnesses = {1.0f, 2.0f, 3.0f};  // per edge
    EXPECT_EQ(check(mesh).topology.creaseSharpnesses, (std::vector<float>{1.0f, 2.0f, 3.0f}));

    mesh.creaseSharpnesses = {1.0f, 2.0f, 3.0f, 4.0f};
    checked = check(mesh);
    EXPECT_TRUE(checked.topology.creaseEdges.empty());
    EXPECT_EQ(checked.warnings, "/cube.creaseSharpnesses: needs one sharpness per crease (2) or per crease "
                                         "edge (3), found 4; creases ignored\n");
}

TEST(MeshTopology, BadCreasesAndCornersAreReported) {
    MeshPrim mesh = cube();
    mesh.creaseIndices = {0, 2, 3, 40};
    mesh.creaseLengths = {4};
    mesh.creaseSharpnesses = {1.0f, -2.0f, 1.0f};
    mesh.cornerIndices = {7, 9};
    mesh.cornerSharpnesses = {3.0f, 3.0f};
    Checked checked = check(mesh);
    EXPECT_EQ(checked.topology.creaseEdges, (std::vector<int>{0, 2, 2, 3}));
    EXPECT_EQ(checked.topology.creaseSharpnesses, (std::vector<float>{1.0f, 0.0f}));
    EXPECT_EQ(checked.topology.corners, std::vector<int>{7});
    EXPECT_EQ(checked.warnings,
              "/cube.creaseIndices: 1 crease edge names a vertex outside the 8 points (first: crease edge 2); it is "
              "ignored\n"
              "/cube.creaseSharpnesses: 1 crease edge sharpness is negative or not finite (first: crease edge 1); "
              "using 0 (smooth)\n"
              "/cube.cornerIndices: 1 corner names a vertex outside the 8 points (first: corner 1); it is ignored\n");

    mesh.creaseLengths = {3};
    checked = check(mesh);
    EXPECT_TRUE(checked.topology.creaseEdges.empty());
    EXPECT_NE(checked.warnings.find(
                  "/cube.creaseIndices: creaseLengths add up to 3 vertices, found 4; creases ignored\n"),
              std::string::npos)
        << checked.warnings;
}

TEST(MeshTopology, UnknownTokensFallBackWithAWarning) {
    MeshPrim mesh = cube();
    mesh.subdivisionScheme = "doo-sabin";
    mesh.interpolateBoundary = "sometimes";
    mesh.orientation = "sideways";
    const auto [topology, warnings] = check(mesh);
    EXPECT_EQ(topology.scheme, SubdivisionScheme::CatmullClark);
    EXPECT_EQ(topology.boundary, BoundaryInterpolation::EdgeAndCorner);
    EXPECT_EQ(topology.faceVertexIndices, cube().faceVertexIndices);
    EXPECT_EQ(warnings,
              "/cube.subdivisionScheme: unknown value 'doo-sabin' (expected catmullClark, loop, bilinear, none); "
              "using catmullClark\n"
              "/cube.interpolateBoundary: unknown value 'sometimes' (expected none, edgeOnly, edgeAndCorner); "
              "using edgeAndCorner\n"
              "/cube.orientation: unknown value 'sideways' (expected rightHanded, leftHanded); using rightHanded\n");
}

TEST(MeshTopology, LoopOnQuadsIsDrawnAsPolygons) {
    MeshPrim mesh = cube();
    mesh.subdivisionScheme = "loop";
    const auto [topology, warnings] = check(mesh);
    EXPECT_EQ(topology.scheme, SubdivisionScheme::None);
    EXPECT_EQ(warnings,
              "/cube.subdivisionScheme: loop subdivision needs triangles only; drawn as polygons (none)\n");
}
