// Per-pixel fragment lists for exact transparency (an A-buffer): every strand
// fragment is stored, then each pixel sorts its own list by depth and
// composites it exactly. hdHair/gl/FragmentListPass.cpp owns the storage.
#define HDHAIR_LIST_END 0xffffffffu

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
};
