#pragma once
// A Mesh prim as the engine sees it: topology, subdivision tags, points and
// primvars as authored (or as Hydra hands them over), plus its world
// transform. Nothing here is resolved or validated: hdHair/meshes/ does that,
// in one place, for every front end. Meshes are drawn as opaque, diffusely
// lit occluders of the hair (hdHair/meshes/README.md).

#include <map>
#include <string>
#include <tuple>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "hdHair/scene/Primvar.h"

namespace hdhair {

struct MeshPrim {
    std::string path;
    std::string sourceFile;
    std::vector<glm::vec3> points;  // object space
    std::vector<int> faceVertexCounts;
    std::vector<int> faceVertexIndices;
    // UsdGeomMesh's tokens as authored; unknown ones fall back (with a
    // warning) when the mesh is prepared (hdHair/meshes/MeshTopology.h).
    std::string subdivisionScheme = "catmullClark";  // catmullClark, loop, bilinear, none
    std::string orientation = "rightHanded";         // UsdGeomGprim: rightHanded, leftHanded
    std::string interpolateBoundary = "edgeAndCorner";         // none, edgeOnly, edgeAndCorner
    std::string faceVaryingLinearInterpolation = "cornersPlus1";  // none, cornersOnly, cornersPlus1,
                                                                   // cornersPlus2, boundaries, all
    std::string triangleSubdivisionRule = "catmullClark";      // catmullClark, smooth
    // Subdivision tags (UsdGeomMesh): faces left out of the surface, sharp
    // vertices, and creases as chains of vertices (creaseLengths vertices
    // each) with one sharpness per crease or one per edge of the chain.
    std::vector<int> holeIndices;
    std::vector<int> cornerIndices;
    std::vector<float> cornerSharpnesses;
    std::vector<int> creaseIndices;
    std::vector<int> creaseLengths;
    std::vector<float> creaseSharpnesses;
    // "displayColor", "displayOpacity", "normals" and every other primvar,
    // keyed by name without "primvars:".
    std::map<std::string, Primvar> primvars;
    glm::dmat4 worldTransform{1.0};
    bool visible = true;
    // Written to the primId output for picking: Hydra's HdRprim::GetPrimId().
    int primId = -1;
    // Which instance of an instanced prim this is (0 when not instanced).
    int instanceId = 0;
    // Uniform subdivision level for catmullClark and loop: Hydra's display
    // style refine level per prim; -1 takes the meshRefineLevel setting
    // (from --complexity), which is what the .usda reader leaves.
    int refineLevel = -1;

    const Primvar* findPrimvar(const std::string& name) const {
        auto it = primvars.find(name);
        return it == primvars.end() ? nullptr : &it->second;
    }
    // Every member, for operator==: a scene keeps a prim's version when it is
    // set again unchanged (hdhair-record --frames), so nothing is prepared,
    // uploaded or shadowed again. A member added above must be added here;
    // the size check after the struct is there to say so.
    auto fields() const {
        return std::tie(path, sourceFile, points, faceVertexCounts, faceVertexIndices, subdivisionScheme, orientation,
                        interpolateBoundary, faceVaryingLinearInterpolation, triangleSubdivisionRule, holeIndices,
                        cornerIndices, cornerSharpnesses, creaseIndices, creaseLengths, creaseSharpnesses, primvars,
                        worldTransform, visible, primId, instanceId, refineLevel);
    }
    bool operator==(const MeshPrim& other) const { return fields() == other.fields(); }
    bool operator!=(const MeshPrim& other) const { return !(*this == other); }
};
static_assert(sizeof(MeshPrim) == 632, "a member was added to MeshPrim: add it to fields() too (x86-64 size)");

}  // namespace hdhair
