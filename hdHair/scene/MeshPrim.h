#pragma once
// A Mesh prim, kept so that later passes can use it as an occluder.

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
    std::vector<glm::vec3> points;
    std::vector<int> faceVertexCounts;
    std::vector<int> faceVertexIndices;
    std::string subdivisionScheme = "catmullClark";
    std::map<std::string, Primvar> primvars;
    glm::dmat4 worldTransform{1.0};
    bool visible = true;
    // Every member, for operator==: a scene keeps a prim's version when it is
    // set again unchanged (hdhair-record --frames), so nothing is prepared,
    // uploaded or shadowed again. A member added above must be added here;
    // the size check after the struct is there to say so.
    auto fields() const {
        return std::tie(path, sourceFile, points, faceVertexCounts, faceVertexIndices, subdivisionScheme, primvars,
                        worldTransform, visible);
    }
    bool operator==(const MeshPrim& other) const { return fields() == other.fields(); }
    bool operator!=(const MeshPrim& other) const { return !(*this == other); }
};
static_assert(sizeof(MeshPrim) == 352, "a member was added to MeshPrim: add it to fields() too (x86-64 size)");

}  // namespace hdhair
