// shadowMode=reference: every fragment a light view sees, in per-texel lists
// (one layer of the heads image per light's slot), written by
// shadowFragmentList.frag and walked by shadows.glsl: the exact opacity in
// front of any depth, no layers. hdHair/gl/ShadowReferencePass.cpp owns them.
#define HDHAIR_SHADOW_LIST_END 0xffffffffu

struct ShadowNode {
    float depth;   // linear depth in the light's view
    float alpha;   // coverage x opacity in the light's view
    int segment;   // the strand segment: a strand does not shadow itself
    uint next;     // the texel's next node, or HDHAIR_SHADOW_LIST_END
};

layout(std430, binding = 10) buffer ShadowNodes {
    ShadowNode shadowNodes[];
};
layout(r32ui, binding = 1) uniform coherent uimage2DArray shadowListHeads;
