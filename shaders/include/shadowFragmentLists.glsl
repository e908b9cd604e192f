// shadowMode=reference: every fragment a light view sees, in per-texel lists
// (one layer of the heads image per light's slot), written by
// shadowFragmentList.frag and walked by shadows.glsl: the exact opacity in
// front of any depth, no layers. hdHair/gl/ShadowReferencePass.cpp owns them.
//
// One storage block may address only GL_MAX_SHADER_STORAGE_BLOCK_SIZE bytes
// (128 MB on llvmpipe, 11 M nodes), less than a dense groom seen at 4096
// texels needs, so the nodes live in up to HDHAIR_SHADOW_NODE_POOLS pools:
// node n is node n - k size of pool k = n / size, size being pool 0's length
// (the pools after it exist only once pool 0 is as large as a block may be).
#define HDHAIR_SHADOW_LIST_END 0xffffffffu
#define HDHAIR_SHADOW_NODE_POOLS 4

struct ShadowNode {  // 12 bytes (std430)
    float depth;  // linear depth in the light's view
    float alpha;  // coverage x opacity in the light's view
    uint next;    // the texel's next node, or HDHAIR_SHADOW_LIST_END
};

layout(std430, binding = 10) buffer ShadowNodes0 { ShadowNode shadowNodes0[]; };
layout(std430, binding = 12) buffer ShadowNodes1 { ShadowNode shadowNodes1[]; };
layout(std430, binding = 13) buffer ShadowNodes2 { ShadowNode shadowNodes2[]; };
layout(std430, binding = 14) buffer ShadowNodes3 { ShadowNode shadowNodes3[]; };
layout(r32ui, binding = 1) uniform coherent uimage2DArray shadowListHeads;

uint shadowPoolSize() { return uint(shadowNodes0.length()); }

ShadowNode readShadowNode(uint node) {
    uint size = shadowPoolSize();
    if (node < size) return shadowNodes0[node];
    if (node < 2u * size) return shadowNodes1[node - size];
    if (node < 3u * size) return shadowNodes2[node - 2u * size];
    return shadowNodes3[node - 3u * size];
}

void writeShadowNode(uint node, ShadowNode value) {
    uint size = shadowPoolSize();
    if (node < size) shadowNodes0[node] = value;
    else if (node < 2u * size) shadowNodes1[node - size] = value;
    else if (node < 3u * size) shadowNodes2[node - 2u * size] = value;
    else shadowNodes3[node - 3u * size] = value;
}
