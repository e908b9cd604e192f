#pragma once
// Draws meshes (MeshGeometry) as opaque triangles from any view-projection:
// depth tested (LESS) and written, no face culled. Shaded, they write colour
// (Lambert under the bound light block, or displayColor unlit), the ids and
// the nearest depth, as the frame's other opaque geometry would; seen from a
// light, they write the nearest mesh's linear depth (ShadowMapPass).

#include <cstddef>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include "hdHair/gl/GlObjects.h"
#include "hdHair/gl/MeshGeometry.h"

namespace hdhair::gl {

// One mesh's vertices in the MeshGeometry buffer, and its ids.
struct MeshDraw {
    size_t first = 0, count = 0;  // vertices, 3 a triangle
    glm::ivec2 primAndInstance{-1, 0};
    bool operator==(const MeshDraw& other) const {
        return first == other.first && count == other.count && primAndInstance == other.primAndInstance;
    }
};

enum class MeshShading {
    Lit,       // Lambert under the light block at binding 1 (StrandPass::setUniforms)
    Unlit,     // displayColor, in the first light batch only (LightUniforms::lightCount.y == 0)
    LightDepth  // linear depth in the light view of the bound shadow uniforms' entry 0, min-blended
};

class MeshPass {
public:
    MeshPass();  // compiles the programs; throws on driver errors

    // Draws into the bound framebuffer. Shaded draws need the light block
    // bound (binding 1), also when unlit (the batch number), and the shadow
    // block (binding 2) with its maps; LightDepth draws the shadow block.
    void draw(const MeshGeometry& geometry, const std::vector<MeshDraw>& draws, const glm::mat4& viewProjection,
              MeshShading shading);

private:
    Program shaded_, lightDepth_;
    VertexArray emptyVertexArray_;  // core profile draws need one bound
};

}  // namespace hdhair::gl
