#pragma once
// A mesh's topology, checked and repaired once, before anything refines or
// draws it: what every front end's MeshPrim becomes (hdHair/meshes/README.md
// lists the rules). Faces that cannot be drawn are left out, and everything
// downstream refers back to the authored faces and corners, so elementIds,
// uniform and faceVarying primvars keep the authored numbering.
//
// Bad input is never fatal and never sizes an allocation by itself: every
// repair is one warning at "<prim>.<attribute>" saying what was done.

#include <cstddef>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace hdhair {

class Diagnostics;
struct MeshPrim;

enum class SubdivisionScheme { CatmullClark, Loop, Bilinear, None };
const char* toString(SubdivisionScheme scheme);

// UsdGeomMesh's interpolateBoundary, faceVaryingLinearInterpolation and
// triangleSubdivisionRule, in OpenSubdiv's order (Sdc::Options).
enum class BoundaryInterpolation { None, EdgeOnly, EdgeAndCorner };
enum class FaceVaryingInterpolation { None, CornersOnly, CornersPlus1, CornersPlus2, Boundaries, All };
enum class TriangleSubdivision { CatmullClark, Smooth };

struct MeshTopology {
    SubdivisionScheme scheme = SubdivisionScheme::CatmullClark;
    BoundaryInterpolation boundary = BoundaryInterpolation::EdgeAndCorner;
    FaceVaryingInterpolation faceVarying = FaceVaryingInterpolation::CornersPlus1;
    TriangleSubdivision triangles = TriangleSubdivision::CatmullClark;

    // The cage: the authored points, with non-finite ones replaced (the
    // faces using them are holes), and the faces that can be drawn, wound
    // counter-clockwise seen from their front (leftHanded faces reversed).
    std::vector<glm::vec3> points;
    std::vector<int> faceVertexCounts;
    std::vector<int> faceVertexIndices;
    // Per kept face: its index among the authored faces (the elementId and
    // the uniform primvar element).
    std::vector<int> authoredFace;
    // Per kept face corner, in faceVertexIndices' order: its index among the
    // authored faceVertexIndices (the faceVarying primvar element).
    std::vector<int> authoredCorner;
    std::vector<bool> hole;  // per kept face

    // Sharpness per edge (vertex pairs) and per vertex, valid indices only.
    std::vector<int> creaseEdges;  // 2 per edge
    std::vector<float> creaseSharpnesses;
    std::vector<int> corners;
    std::vector<float> cornerSharpnesses;

    // What the primvars of the authored prim are counted against.
    size_t authoredFaceCount = 0;    // uniform
    size_t authoredPointCount = 0;   // vertex and varying
    size_t authoredCornerCount = 0;  // faceVarying

    size_t faceCount() const { return faceVertexCounts.size(); }
};

// Checks `prim` and returns what can be drawn of it; each repair is reported
// to `diagnostics` (see hdHair/meshes/README.md, "Repairs").
MeshTopology checkMeshTopology(const MeshPrim& prim, Diagnostics& diagnostics);

}  // namespace hdhair
