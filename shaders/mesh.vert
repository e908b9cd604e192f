#version 450 core
#extension GL_GOOGLE_include_directive : require
// Pulls each mesh vertex from the mesh buffer by gl_VertexID (glDrawArrays
// starts it at the mesh's first vertex): no vertex attributes. The view-
// projection is the pass's own, so the same stage draws from the camera or,
// depth only, from a light.
#include "include/meshGeometry.glsl"

layout(location = 0) out vec3 worldPosition;
layout(location = 1) out vec3 worldNormal;
layout(location = 2) out vec3 color;
layout(location = 3) flat out int face;

void main() {
    MeshVertex vertex = meshVertices[gl_VertexID];
    worldPosition = vertex.position;
    worldNormal = vertex.normal;
    color = vertex.color;
    face = vertex.face;
    gl_Position = meshViewProjection * vec4(vertex.position, 1.0);
}
