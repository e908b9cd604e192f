#pragma once
// The GPU copy of every mesh a frame draws: their triangles' vertices
// (hdHair/meshes/PreparedMesh.h MeshVertex), all meshes in one storage
// buffer read by shaders/mesh.vert (binding 8). Meshes are few and small
// next to the strands, so the renderer rewrites the whole buffer when any
// drawn mesh changed and sends nothing otherwise.

#include <cstddef>
#include <vector>

#include "hdHair/gl/GlObjects.h"

namespace hdhair {
struct MeshVertex;
}

namespace hdhair::gl {

class MeshGeometry {
public:
    size_t capacity() const { return capacity_; }  // in vertices
    // Makes room for at least `vertices`; what was there is dropped (every
    // mesh is written again after a change).
    void reserve(size_t vertices);
    // Writes `vertices` at [first, first + vertices.size()).
    void write(size_t first, const std::vector<MeshVertex>& vertices);
    // Binds the buffer at binding 8 (shaders/include/meshGeometry.glsl).
    void bind() const;

private:
    Buffer vertices_;
    size_t capacity_ = 0;
};

}  // namespace hdhair::gl
