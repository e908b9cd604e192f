#pragma once
// A Mesh prim, kept so that later passes can use it as an occluder.

#include <map>
#include <string>
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
};

}  // namespace hdhair
