#version 450 core
#extension GL_GOOGLE_include_directive : require
// Per-pixel fragment lists, pass 2: each pixel sorts its fragments by depth
// and composites them front to back with the over operator:
//   C = sum_i T_i c_i,  A = 1 - T_n,  T_i = prod_{j<i} (1 - a_j)
// (c_i pre-multiplied). Lists that fit in registers are insertion-sorted;
// longer ones, up to SELECTED_FRAGMENTS, are walked in depth order by
// repeated selection, which is O(k^2) but exact: this pass is the ground
// truth. A longer list (hundreds of strands in one pixel) has its nearest
// LOCAL_FRAGMENTS composited exactly and the rest behind them as one layer,
// their pre-multiplied colours averaged by alpha, with their total
// transmittance (weighted average order-independent transparency, Bavoil
// and Myers 2008); the pixel is counted (overlongLists) and the renderer
// warns. llvmpipe ends a shader invocation's loops after 65535 iterations
// in all (gallivm's loop limiter, one count for every loop of the
// invocation): SELECTED_FRAGMENTS keeps the selection under it, and a list
// too long to walk whole within it is counted too (unwalkedLists), its
// farthest-appended fragments left out, and the renderer says so.
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
#define SELECTED_FRAGMENTS 180u

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
        if (definesDepthAndIds(nodes[n].color.a) &&
            (front == HDHAIR_LIST_END || nearer(nodes[n].depth, n, nodes[front].depth, front)))
            front = n;
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
    // An empty list adds nothing: (0, 0) over the frame, depth 1 under the
    // min blend, no ids. Most of a hair frame's pixels have none.
    if (head == HDHAIR_LIST_END) discard;
    if (resolveIds != 0) {
        writeIds(head);
        return;
    }
    vec4 color = vec4(0.0);
    float transmittance = 1.0;
    // The nearest fragment that may define depth: what a user picks.
    bool front = false;
    float frontDepth = 1.0;

    // One walk keeps the nearest LOCAL_FRAGMENTS sorted, nearest first, on
    // copies of the depths held in registers (Mesa 22.3's llvmpipe
    // composited wrong lists when the sort read depths from the storage
    // buffer inside its loop condition), and sums those behind them.
    uint local[LOCAL_FRAGMENTS];
    float localDepth[LOCAL_FRAGMENTS];
    int count = 0;
    uint total = 0u;
    vec3 tailColor = vec3(0.0);
    float tailAlpha = 0.0, tailTransmittance = 1.0;
    uint n = head;
    for (; n != HDHAIR_LIST_END && n < capacity; ++total) {
        uint key = n;
        float keyDepth = nodes[n].depth;
        n = nodes[n].next;
        if (count == LOCAL_FRAGMENTS) {
            if (!nearer(keyDepth, key, localDepth[LOCAL_FRAGMENTS - 1], local[LOCAL_FRAGMENTS - 1])) {
                vec4 behind = nodes[key].color;
                tailColor += behind.rgb;
                tailAlpha += behind.a;
                tailTransmittance *= 1.0 - behind.a;
                continue;
            }
            // The farthest kept one moves behind.
            vec4 evicted = nodes[local[LOCAL_FRAGMENTS - 1]].color;
            tailColor += evicted.rgb;
            tailAlpha += evicted.a;
            tailTransmittance *= 1.0 - evicted.a;
            --count;
        }
        // Insertion, nearest first.
        int j = count - 1;
        while (j >= 0 && nearer(keyDepth, key, localDepth[j], local[j])) {
            local[j + 1] = local[j];
            localDepth[j + 1] = localDepth[j];
            --j;
        }
        local[j + 1] = key;
        localDepth[j + 1] = keyDepth;
        ++count;
    }
    // The loop limiter ended the walk before the list's end.
    if (n != HDHAIR_LIST_END && n < capacity) atomicAdd(unwalkedLists, 1u);

    if (total <= uint(LOCAL_FRAGMENTS) || total > SELECTED_FRAGMENTS) {
        for (int i = 0; i < count; ++i) {
            FragmentNode node = nodes[local[i]];
            if (!front && definesDepthAndIds(node.color.a)) {
                front = true;
                frontDepth = node.depth;
            }
            color.rgb += transmittance * node.color.rgb;
            transmittance *= 1.0 - node.color.a;
        }
        if (total > SELECTED_FRAGMENTS) {
            // The tail as one layer behind the nearest ones.
            if (tailAlpha > 0.0) color.rgb += transmittance * tailColor / tailAlpha * (1.0 - tailTransmittance);
            transmittance *= tailTransmittance;
            atomicAdd(overlongLists, 1u);
        }
    } else {
        // Select the next-nearest fragment after the last one taken, until none is left.
        float lastDepth = -1.0;
        uint lastIndex = 0u;
        bool first = true;
        for (uint taken = 0u; taken < total; ++taken) {
            uint best = HDHAIR_LIST_END;
            for (uint m = head; m != HDHAIR_LIST_END && m < capacity; m = nodes[m].next) {
                bool after = first || nearer(lastDepth, lastIndex, nodes[m].depth, m);
                if (after && (best == HDHAIR_LIST_END || nearer(nodes[m].depth, m, nodes[best].depth, best))) best = m;
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
