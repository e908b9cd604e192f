#version 450 core
#extension GL_GOOGLE_include_directive : require
// One tile of the fragment lists' image an instance, as two triangles
// (vertices 0-5), clamped to the image: the resolve's coverage
// (fragmentListTiles.comp gathers the tiles).
#include "include/fragmentLists.glsl"
#include "include/resolvedTiles.glsl"

layout(location = 1) uniform ivec2 imageSize;

void main() {
    const vec2 corners[6] = vec2[6](vec2(0.0, 0.0), vec2(1.0, 0.0), vec2(0.0, 1.0), vec2(0.0, 1.0), vec2(1.0, 0.0),
                                    vec2(1.0, 1.0));
    uint tilesPerRow = listTilesPerRow(imageSize.x);
    uint tile = resolvedTiles[gl_InstanceID];
    vec2 origin = vec2(float(tile % tilesPerRow), float(tile / tilesPerRow));
    vec2 pixels = min((origin + corners[gl_VertexID]) * float(HDHAIR_LIST_TILE), vec2(imageSize));
    gl_Position = vec4(pixels / vec2(imageSize) * 2.0 - 1.0, 0.0, 1.0);
}
