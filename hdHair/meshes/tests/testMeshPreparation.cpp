// prepareMesh: triangles in world space with their authored faces, colours
// at every interpolation, normals on the front side whatever the
// orientation or transform, and hard input that stays finite.

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "TestMeshes.h"
#include "hdHair/base/Diagnostics.h"
#include "hdHair/meshes/PreparedMesh.h"
#include "hdHair/scene/tests/AuthoredPrimvar.h"

using namespace hdhair;
using hdhair::test::authoredPrimvar;
using hdhair::test::cube;
using hdhair::test::quadGrid;
using hdhair::test::warningsText;

namespace {

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Every vertex finite with a unit normal, and every triangle of area wound
// counter-clockwise seen from the side its normals point to.
void expectWellFormed(const PreparedMesh& mesh) {
    ASSERT_EQ(mesh.vertices.size() % 3, 0u);
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
        const MeshVertex* v = &mesh.vertices[3 * t];
        const glm::vec3 area = glm::cross(v[1].position - v[0].position, v[2].position - v[0].position);
        for (int k = 0; k < 3; ++k) {
            ASSERT_TRUE(finite(v[k].position) && finite(v[k].normal) && finite(v[k].color)) << "triangle " << t;
            EXPECT_NEAR(glm::length(v[k].normal), 1.0f, 1e-5f);
            EXPECT_EQ(v[k].face, v[0].face);
            if (glm::length(area) > 1e-6f) {
                EXPECT_GT(glm::dot(area, v[k].normal), 0.0f) << "triangle " << t;
            }
        }
    }
}

}  // namespace

TEST(MeshPreparation, PolygonsAreFanTriangulatedWithTheirAuthoredFaces) {
    MeshPrim mesh = quadGrid(2);
    mesh.faceVertexCounts = {4, 2, 4, 4, 4};  // face 1 is left out
    mesh.faceVertexIndices = {0, 1, 4, 3, 0, 1, 1, 2, 5, 4, 3, 4, 7, 6, 4, 5, 8, 7};
    mesh.worldTransform = glm::translate(glm::dmat4(1.0), glm::dvec3(10.0, 0.0, 0.0));
    Diagnostics diagnostics;
    const PreparedMesh prepared = prepareMesh(mesh, 3, diagnostics);
    EXPECT_EQ(prepared.scheme, SubdivisionScheme::None);
    EXPECT_EQ(prepared.refineLevel, 0);
    ASSERT_EQ(prepared.triangleCount(), 8u);
    EXPECT_EQ(prepared.vertices[0].position, glm::vec3(10, 0, 0));
    EXPECT_EQ(prepared.vertices[1].position, glm::vec3(11, 0, 0));
    EXPECT_EQ(prepared.vertices[2].position, glm::vec3(11, 1, 0));
    const std::vector<int> faces = {0, 0, 2, 2, 3, 3, 4, 4};
    for (size_t t = 0; t < 8; ++t) EXPECT_EQ(prepared.vertices[3 * t].face, faces[t]);
    EXPECT_EQ(prepared.vertices[0].normal, glm::vec3(0, 0, 1));
    EXPECT_EQ(prepared.boundsMin, glm::vec3(10, 0, 0));
    EXPECT_EQ(prepared.boundsMax, glm::vec3(12, 2, 0));
    expectWellFormed(prepared);
}

TEST(MeshPreparation, ColoursAtEveryInterpolation) {
    MeshPrim mesh = quadGrid(2);  // 4 faces, 9 points, 16 corners
    auto colorOf = [](float i) { return glm::vec3(i / 16.0f, 1.0f - i / 16.0f, 0.25f); };
    auto values = [&](size_t n) {
        std::vector<float> v;
        for (size_t i = 0; i < n; ++i) {
            const glm::vec3 c = colorOf(float(i));
            v.insert(v.end(), {c.r, c.g, c.b});
        }
        return v;
    };
    Diagnostics diagnostics;
    // Uniform: each triangle has its face's colour.
    mesh.primvars["displayColor"] = authoredPrimvar("displayColor", Interpolation::Uniform, 3, values(4));
    PreparedMesh prepared = prepareMesh(mesh, 0, diagnostics);
    for (const MeshVertex& v : prepared.vertices) EXPECT_EQ(v.color, colorOf(float(v.face)));
    // Vertex (and varying): each corner has its point's colour.
    for (Interpolation interpolation : {Interpolation::Vertex, Interpolation::Varying}) {
        mesh.primvars["displayColor"] = authoredPrimvar("displayColor", interpolation, 3, values(9));
        prepared = prepareMesh(mesh, 0, diagnostics);
        for (const MeshVertex& v : prepared.vertices)
            EXPECT_EQ(v.color, colorOf(v.position.y * 3.0f + v.position.x)) << toString(interpolation);
    }
    // FaceVarying, indexed: corner k of face f has value (f + k) % 3.
    Primvar faceVarying = authoredPrimvar("displayColor", Interpolation::FaceVarying, 3, values(3));
    for (int f = 0; f < 4; ++f)
        for (int k = 0; k < 4; ++k) faceVarying.indices.push_back((f + k) % 3);
    mesh.primvars["displayColor"] = faceVarying;
    prepared = prepareMesh(mesh, 0, diagnostics);
    // Triangle 2f is corners (0, 1, 2) of face f, triangle 2f + 1 corners (0, 2, 3).
    for (size_t t = 0; t < prepared.triangleCount(); ++t) {
        const int f = int(t / 2);
        const int corners[2][3] = {{0, 1, 2}, {0, 2, 3}};
        for (int j = 0; j < 3; ++j)
            EXPECT_EQ(prepared.vertices[3 * t + size_t(j)].color, colorOf(float((f + corners[t % 2][j]) % 3)));
    }
    EXPECT_EQ(diagnostics.warningCount(), 0u) << warningsText(diagnostics);
}

// Catmull-Clark with one colour per face as faceVarying (non-indexed: a seam
// at every edge): every refined triangle keeps its authored face and colour.
TEST(MeshPreparation, RefinedTrianglesKeepTheirAuthoredFaceAndFaceVaryingColour) {
    MeshPrim mesh = cube();
    std::vector<float> perCorner;
    for (int corner = 0; corner < 24; ++corner) perCorner.insert(perCorner.end(), {float(corner / 4) / 5.0f, 0.0f, 1.0f});
    mesh.primvars["displayColor"] = authoredPrimvar("displayColor", Interpolation::FaceVarying, 3, perCorner);
    Diagnostics diagnostics;
    const PreparedMesh prepared = prepareMesh(mesh, 2, diagnostics);
    EXPECT_EQ(diagnostics.warningCount(), 0u) << warningsText(diagnostics);
    EXPECT_EQ(prepared.refineLevel, 2);
    EXPECT_EQ(prepared.triangleCount(), 6u * 16u * 2u);
    for (const MeshVertex& v : prepared.vertices) {
        EXPECT_NEAR(v.color.r, float(v.face) / 5.0f, 1e-6f);
        // The face's axis: faces 0, 1 are z, 2, 3 y, 4, 5 x; -1 for the even ones.
        const glm::vec3 axis = glm::vec3(v.face / 2 == 2, v.face / 2 == 1, v.face / 2 == 0) * (v.face % 2 ? 1.0f : -1.0f);
        EXPECT_GT(glm::dot(v.normal, axis), 0.0f) << "face " << v.face;
        EXPECT_GT(glm::dot(v.normal, glm::normalize(v.position)), 0.5f);
    }
    expectWellFormed(prepared);
}

TEST(MeshPreparation, LeftHandedWindingAndMirroringTransformsKeepNormalsOutward) {
    for (const char* scheme : {"none", "catmullClark"}) {
        MeshPrim rightHanded = cube();
        rightHanded.subdivisionScheme = scheme;
        MeshPrim leftHanded = rightHanded;
        leftHanded.orientation = "leftHanded";
        for (size_t f = 0; f < 6; ++f) std::swap(leftHanded.faceVertexIndices[4 * f + 1], leftHanded.faceVertexIndices[4 * f + 3]);
        MeshPrim mirrored = rightHanded;
        mirrored.worldTransform = glm::scale(glm::dmat4(1.0), glm::dvec3(-1.0, 2.0, 1.0));
        Diagnostics diagnostics;
        for (const MeshPrim* mesh : {&rightHanded, &leftHanded, &mirrored}) {
            const PreparedMesh prepared = prepareMesh(*mesh, 1, diagnostics);
            expectWellFormed(prepared);
            for (const MeshVertex& v : prepared.vertices)
                EXPECT_GT(glm::dot(v.normal, v.position), 0.0f) << scheme << " " << mesh->orientation;
        }
        EXPECT_EQ(diagnostics.warningCount(), 0u) << warningsText(diagnostics);
    }
}

TEST(MeshPreparation, ZeroAreaFacesAndNonFinitePointsStayFinite) {
    for (const char* scheme : {"none", "catmullClark", "bilinear"}) {
        MeshPrim mesh = quadGrid(3);
        mesh.subdivisionScheme = scheme;
        mesh.points[5] = glm::vec3(std::numeric_limits<float>::quiet_NaN());
        mesh.points[10] = mesh.points[11];  // faces 5 and 8 get two corners in one place
        mesh.points.insert(mesh.points.end(), {{5, 0, 0}, {6, 0, 0}, {7, 0, 0}});
        mesh.faceVertexCounts.push_back(3);
        mesh.faceVertexIndices.insert(mesh.faceVertexIndices.end(), {16, 17, 18});  // a line: no area
        Diagnostics diagnostics;
        const PreparedMesh prepared = prepareMesh(mesh, 2, diagnostics);
        EXPECT_FALSE(prepared.empty());
        expectWellFormed(prepared);
        const std::string warnings = warningsText(diagnostics);
        EXPECT_NE(warnings.find("/grid.points: 1 point is not finite (first: points[5]); the faces using it are not "
                                "drawn"),
                  std::string::npos)
            << scheme << ": " << warnings;
        EXPECT_NE(warnings.find("/grid.faceVertexCounts: 1 face has no area (first: face 9)"), std::string::npos)
            << scheme << ": " << warnings;
        for (const MeshVertex& v : prepared.vertices) EXPECT_NE(v.face, 0);  // face 0 uses point 5
    }
}

TEST(MeshPreparation, TheRefineLevelIsLoweredToStayUnderTheTriangleLimit) {
    Diagnostics diagnostics;
    const MeshTopology topology = checkMeshTopology(cube(), diagnostics);
    // 6 quads: 24 corners, so 48 * 4^(level - 1) triangles.
    EXPECT_EQ(refinedTriangleCount(topology, 0), 12.0);
    EXPECT_EQ(refinedTriangleCount(topology, 1), 48.0);
    EXPECT_EQ(refinedTriangleCount(topology, 3), 768.0);
    EXPECT_EQ(affordableRefineLevel(topology, 8, 768), 3);
    EXPECT_EQ(affordableRefineLevel(topology, 8, 767), 2);
    EXPECT_EQ(affordableRefineLevel(topology, 8, 1), 0);
    MeshPrim loop = test::octahedron();
    EXPECT_EQ(refinedTriangleCount(checkMeshTopology(loop, diagnostics), 2), 128.0);
    // The prim's own level wins over the setting's; scheme none is never refined.
    MeshPrim mesh = cube();
    mesh.refineLevel = 1;
    EXPECT_EQ(prepareMesh(mesh, 3, diagnostics).triangleCount(), 48u);
    // kMaxMeshTriangles: the cube at level 8 makes 786,432 (under it); a
    // 6 x 6 grid at level 8 would make 2 * 144 * 4^7 = 4,718,592 and is
    // refined to level 6 (294,912).
    MeshPrim grid = quadGrid(6);
    grid.subdivisionScheme = "catmullClark";
    const PreparedMesh lowered = prepareMesh(grid, 8, diagnostics);
    EXPECT_EQ(lowered.refineLevel, 6);
    EXPECT_EQ(lowered.triangleCount(), 294912u);
    EXPECT_EQ(warningsText(diagnostics), "/grid: refine level 8 would make 4718592 triangles, more than 1000000; "
                                         "refined to level 6 instead\n");
}

TEST(MeshPreparation, TranslucentMeshesAreDrawnOpaqueWithAWarning) {
    MeshPrim mesh = quadGrid(1);
    mesh.primvars["displayOpacity"] = authoredPrimvar("displayOpacity", Interpolation::Vertex, 1, {1, 1, 0.25f, 1});
    Diagnostics diagnostics;
    prepareMesh(mesh, 0, diagnostics);
    EXPECT_EQ(warningsText(diagnostics),
              "/grid.primvars:displayOpacity: opacity down to 0.25: hdHair draws meshes opaque\n");
}
