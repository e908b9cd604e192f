// Every drawn mesh's triangles, three vertices each, in world space
// (hdHair/meshes/PreparedMesh.h MeshVertex mirrors the struct; std430).
// hdHair/gl/MeshGeometry.cpp owns the buffer.
struct MeshVertex {
    vec3 position;
    int face;        // the authored face: the elementId
    vec3 normal;     // unit, on the front side
    float unused0;
    vec3 color;      // linear displayColor
    float unused1;
};

layout(std430, binding = 8) readonly buffer MeshVertices {
    MeshVertex meshVertices[];
};

// Uniforms of the mesh programs (hdHair/gl/MeshPass.cpp sets them by location).
layout(location = 0) uniform mat4 meshViewProjection;
