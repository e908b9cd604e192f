#version 450 core
#extension GL_GOOGLE_include_directive : require
// Exact transparency, pass 2: each pixel sorts its fragments by depth and
// composites them front to back with the over operator:
//   C = sum_i T_i c_i,  A = 1 - T_n,  T_i = prod_{j<i} (1 - a_j)
// (c_i pre-multiplied). Lists that fit in registers are insertion-sorted;
// longer ones are walked in depth order by repeated selection, which is
// O(k^2) but exact for any length: this pass is the ground truth.
// Depth and ids come from the nearest fragment that definesDepthAndIds()
// accepts, as in the other blended paths.
// Opaque geometry drawn before (meshes) stays behind the lists: the pass
// draws twice (hdHair/gl/FragmentListPass.cpp). resolveIds 0: the colour,
// composited over what the frame holds, and the nearest depth, min-blended
// with it; resolveIds 1: the ids, only where a listed fragment defines them
// (elsewhere the frame keeps its ids: the mesh's, or -1).
#include "include/frameUniforms.glsl"
#include "include/fragmentLists.glsl"
#include "include/strandGeometry.glsl"

#define LOCAL_FRAGMENTS 64

layout(r32ui, binding = 0) uniform readonly uimage2D listHeads;

layout(location = 0) out vec4 outColor;
layout(location = 1) out int outPrimId;
layout(location = 2) out int outInstanceId;
layout(location = 3) out int outElementId;
layout(location = 4) out float outNearestDepth;  // hdHair/gl/RenderTarget.h kNearestDepthOutput

layout(location = 0) uniform int resolveIds;

// Orders fragments by depth, then by index, so ties resolve the same way
// whatever order the GPU appended them in.
bool nearer(float depthA, uint indexA, float depthB, uint indexB) {
    return depthA < depthB || (depthA == depthB && indexA < indexB);
}

// The ids of the nearest fragment that may define them; no sort needed.
void writeIds(uint head) {
    uint front = HDHAIR_LIST_END;
    for (uint n = head; n != HDHAIR_LIST_END && n < capacity; n = nodes[n].next) {
        if (!definesDepthAndIds(nodes[n].color.a)) continue;
        if (front == HDHAIR_LIST_END || nearer(nodes[n].depth, n, nodes[front].depth, front)) front = n;
    }
    if (front == HDHAIR_LIST_END) discard;
    int segment = nodes[front].segment;
    ivec2 primAndInstance = segmentPrimAndInstance(segment);
    outPrimId = primAndInstance.x;
    outInstanceId = primAndInstance.y;
    outElementId = segmentCurve[segment];
}

void main() {
    uint head = imageLoad(listHeads, ivec2(gl_FragCoord.xy)).r;
    if (resolveIds != 0) {
        writeIds(head);
        return;
    }
    vec4 color = vec4(0.0);
    float transmittance = 1.0;
    // The nearest fragment that may define depth: what a user picks.
    bool front = false;
    float frontDepth = 1.0;

    // Gather first, sort afterwards, on copies of the depths held in
    // registers: Mesa 22.3's llvmpipe composited wrong lists when the sort
    // read depths from the storage buffer inside its loop condition.
    uint local[LOCAL_FRAGMENTS];
    float localDepth[LOCAL_FRAGMENTS];
    int count = 0;
    bool fits = true;
    for (uint n = head; n != HDHAIR_LIST_END && n < capacity; n = nodes[n].next) {
        if (count == LOCAL_FRAGMENTS) {
            fits = false;
            break;
        }
        local[count] = n;
        localDepth[count] = nodes[n].depth;
        ++count;
    }
    // Insertion sort, nearest first.
    for (int i = 1; i < count; ++i) {
        uint key = local[i];
        float keyDepth = localDepth[i];
        int j = i - 1;
        while (j >= 0 && nearer(keyDepth, key, localDepth[j], local[j])) {
            local[j + 1] = local[j];
            localDepth[j + 1] = localDepth[j];
            --j;
        }
        local[j + 1] = key;
        localDepth[j + 1] = keyDepth;
    }

    if (fits) {
        for (int i = 0; i < count; ++i) {
            FragmentNode node = nodes[local[i]];
            if (!front && definesDepthAndIds(node.color.a)) {
                front = true;
                frontDepth = node.depth;
            }
            color.rgb += transmittance * node.color.rgb;
            transmittance *= 1.0 - node.color.a;
        }
    } else {
        // Select the next-nearest fragment after the last one taken, until none is left.
        float lastDepth = -1.0;
        uint lastIndex = 0u;
        bool first = true;
        for (;;) {
            uint best = HDHAIR_LIST_END;
            for (uint n = head; n != HDHAIR_LIST_END && n < capacity; n = nodes[n].next) {
                bool after = first || nearer(lastDepth, lastIndex, nodes[n].depth, n);
                if (after && (best == HDHAIR_LIST_END || nearer(nodes[n].depth, n, nodes[best].depth, best))) best = n;
            }
            if (best == HDHAIR_LIST_END) break;
            FragmentNode node = nodes[best];
            if (!front && definesDepthAndIds(node.color.a)) {
                front = true;
                frontDepth = node.depth;
            }
            color.rgb += transmittance * node.color.rgb;
            transmittance *= 1.0 - node.color.a;
            lastDepth = node.depth;
            lastIndex = best;
            first = false;
        }
    }
    color.a = 1.0 - transmittance;
    outColor = color;
    outNearestDepth = frontDepth;
}
