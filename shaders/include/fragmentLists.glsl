// Per-pixel fragment lists for exact transparency (an A-buffer): every strand
// fragment is stored, then each pixel sorts its own list by depth and
// composites it exactly. hdHair/gl/FragmentListPass.cpp owns the storage.
#define HDHAIR_LIST_END 0xffffffffu
// The resolve draws only the square tiles of this many pixels a side where
// some fragment was appended (fragmentListTiles.comp); FragmentListPass.h's
// kFragmentListTile.
#define HDHAIR_LIST_TILE 16

struct FragmentNode {
    vec4 color;     // pre-multiplied RGB and alpha
    float depth;    // window depth
    uint next;      // next node of the same pixel, or HDHAIR_LIST_END
    int segment;    // the strand segment, for the ids (strandGeometry.glsl)
};

layout(std430, binding = 5) buffer FragmentNodes {
    FragmentNode nodes[];
};
// fragmentCount counts every fragment offered, also those past capacity, so
// the CPU can tell how much memory the frame needed.
layout(std430, binding = 6) buffer FragmentCounter {
    uint fragmentCount;
    uint capacity;
    // Pixels whose lists were too long to sort whole, and too long to walk
    // whole (fragmentListResolve.frag).
    uint overlongLists;
    uint unwalkedLists;
    // Per tile of the lists' image, row by row: 1 where a fragment was
    // appended since fragmentListTiles.comp last gathered (and cleared) them.
    uint tileHasFragments[];
};

uint listTilesPerRow(int width) { return uint(width + HDHAIR_LIST_TILE - 1) / uint(HDHAIR_LIST_TILE); }

#ifdef HDHAIR_FRAGMENT_LIST_APPEND
layout(r32ui, binding = 0) uniform coherent uimage2D listHeads;

// Appends a shaded fragment (pre-multiplied colour and alpha, window depth,
// its segment for the ids) to its pixel's list, and marks the pixel's tile.
void appendFragmentNode(ivec2 pixel, vec4 premultiplied, float depth, int segment) {
    uint tile = uint(pixel.y / HDHAIR_LIST_TILE) * listTilesPerRow(imageSize(listHeads).x) +
                uint(pixel.x / HDHAIR_LIST_TILE);
    // Read first: most fragments land in a tile already marked, and a store
    // to a shared line costs more than a load.
    if (tileHasFragments[tile] == 0u) tileHasFragments[tile] = 1u;
    uint index = atomicAdd(fragmentCount, 1u);
    if (index >= capacity) return;  // over budget: the CPU sees the count and falls back
    uint previous = imageAtomicExchange(listHeads, pixel, index);
    nodes[index] = FragmentNode(premultiplied, depth, previous, segment);
}
#endif
