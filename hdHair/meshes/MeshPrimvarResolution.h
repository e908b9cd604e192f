#pragma once
// Primvar resolution for meshes: the shared flattening and repairs
// (hdHair/scene/PrimvarFlattening.h) with a mesh's element counts, so a mesh
// primvar is checked, repaired and reported the same way from every front
// end, and the same way as a curves primvar would be.
//
// Element counts (UsdGeomMesh): constant 1; uniform one per authored face;
// vertex and varying one per point; faceVarying one per authored face
// corner (faceVertexIndices). A primvar of another count, or of another
// tuple size than the fallback, resolves to the constant fallback with a
// warning naming the prim, the primvar, the count needed and the count found;
// indices are followed (an out-of-range index gives the fallback for that
// element) and non-finite elements are replaced by the fallback.

#include <string>
#include <vector>

#include "hdHair/scene/PrimvarFlattening.h"

namespace hdhair {

class Diagnostics;
struct MeshPrim;
struct MeshTopology;

ResolvedPrimvar resolveMeshPrimvar(const Primvar& primvar, const MeshTopology& topology,
                                   const std::vector<float>& fallback, const std::string& primPath,
                                   const std::string& primvarName, Diagnostics& diagnostics);

// Resolves prim.primvars[name] when authored, else returns constantPrimvar(fallback).
ResolvedPrimvar resolveMeshPrimvar(const MeshPrim& prim, const MeshTopology& topology, const std::string& primvarName,
                                   const std::vector<float>& fallback, Diagnostics& diagnostics);

}  // namespace hdhair
