// The tiles of the fragment lists' image that hold fragments, as an indirect
// draw of one quad (six vertices) a tile, instanced over them:
// fragmentListTiles.comp writes it, fragmentListTile.vert reads it, and
// FragmentListPass.cpp draws it (glDrawArraysIndirect, the command first).
layout(std430, binding = 9) buffer ResolvedTiles {
    // DrawArraysIndirectCommand (OpenGL 4.5 core, section 10.4).
    uint tileVertexCount;  // 6
    uint tileCount;        // instances: the tiles gathered
    uint tileFirstVertex;  // 0
    uint tileBaseInstance; // 0
    uint resolvedTiles[];  // tile indices, row by row (fragmentLists.glsl's tileHasFragments)
};
