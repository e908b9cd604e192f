#pragma once
// Wavefront .obj meshes, read with tinyobjloader (Debian's
// libtinyobjloader-dev), for hdhair-convert: the head a groom was made on
// (TressFX's Sintel ships sintel.obj beside sintel_hair.tfx), written as a
// Mesh prim beside the hair in the same units and space.
//
// Every face of every object and group in the file, in file order, as
// authored (polygons are not triangulated); texture coordinates, normals and
// materials are not read (hdHair computes normals from the surface).

#include <string>
#include <vector>

#include "hdHair/assets/TressFxReader.h"

namespace hdhair::convert {

struct PolygonMesh {
    std::string source;     // the file, for messages
    std::vector<Float3> points;
    std::vector<int> faceVertexCounts;
    std::vector<int> faceVertexIndices;
    std::vector<std::string> warnings;  // tinyobjloader's (a missing .mtl file, ...)
};

// Throws std::invalid_argument naming the file for an unreadable or
// malformed file, one without faces, an index outside the vertices or a
// vertex that is not finite.
PolygonMesh readObjMesh(const std::string& path);

}  // namespace hdhair::convert
