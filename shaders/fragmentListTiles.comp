#version 450 core
#extension GL_GOOGLE_include_directive : require
// Per-pixel fragment lists, between their two passes: gathers the tiles where
// some fragment was appended into the instanced draw the resolve takes
// (resolvedTiles.glsl), and clears their marks for the next frame. Most of
// a hair frame's pixels hold no fragment; resolving one still costs a
// fragment shader invocation (on llvmpipe, every branch of it, masked), so
// the resolve covers these tiles rather than the whole viewport.
#include "include/fragmentLists.glsl"
#include "include/resolvedTiles.glsl"

layout(local_size_x = 64) in;

layout(location = 0) uniform uint tilesInImage;

void main() {
    uint tile = gl_GlobalInvocationID.x;
    if (tile >= tilesInImage || tileHasFragments[tile] == 0u) return;
    tileHasFragments[tile] = 0u;
    resolvedTiles[atomicAdd(tileCount, 1u)] = tile;
}
