#include "hdHair/gl/MeshGeometry.h"

#include <algorithm>

#include "hdHair/meshes/PreparedMesh.h"

namespace hdhair::gl {

void MeshGeometry::reserve(size_t vertices) {
    if (vertices <= capacity_ && vertices_) return;
    capacity_ = std::max<size_t>(vertices, 3);
    vertices_ = createBuffer(nullptr, capacity_ * sizeof(MeshVertex), GL_DYNAMIC_STORAGE_BIT, "meshGeometry");
    checkGlError("growing the mesh buffer");
}

void MeshGeometry::write(size_t first, const std::vector<MeshVertex>& vertices) {
    if (vertices.empty()) return;
    glNamedBufferSubData(vertices_.get(), GLintptr(first * sizeof(MeshVertex)),
                         GLsizeiptr(vertices.size() * sizeof(MeshVertex)), vertices.data());
}

void MeshGeometry::bind() const { glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 8, vertices_.get()); }

}  // namespace hdhair::gl
