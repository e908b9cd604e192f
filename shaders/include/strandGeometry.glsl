// The combined strand geometry of every prim drawn in a frame
// (hdHair/gl/StrandGeometry.h). Segment s's four control points start at
// segmentFirstControl[s] (neighbouring spans of a curve share three); each
// control point is two vec4s: (position, width) and (colour, opacity).
layout(std430, binding = 1) readonly buffer ControlPoints {
    vec4 controlPoints[];
};
layout(std430, binding = 15) readonly buffer SegmentFirstControls {
    uint segmentFirstControl[];
};
// Per segment: the curve's index in its prim (Hydra's elementId), and its
// prim's slot in the drawn prims' table.
layout(std430, binding = 2) readonly buffer SegmentCurves {
    int segmentCurve[];
};
layout(std430, binding = 3) readonly buffer SegmentSlots {
    int segmentSlot[];
};
// Segments in drawing order, far to near (used when frame.orderedDraw is 1).
layout(std430, binding = 4) readonly buffer DrawOrder {
    uint drawOrder[];
};
// Per drawn prim: (primId, instanceId, hair material index, 0): Hydra's
// primId and instanceId, and the index into hairMaterials.glsl's materials.
layout(std430, binding = 7) readonly buffer DrawnPrims {
    ivec4 drawnPrims[];
};

// Segment s's four control points, whole: for the stages that read a span
// at once (strandChord.vert, lightViewLevels.comp) rather than a control
// point a vertex (strand.vert).
void segmentControls(uint segment, out vec4 positionWidth[4], out vec4 colorOpacity[4]) {
    uint first = segmentFirstControl[segment];
    for (uint i = 0u; i < 4u; ++i) {
        positionWidth[i] = controlPoints[2u * (first + i)];
        colorOpacity[i] = controlPoints[2u * (first + i) + 1u];
    }
}

ivec2 segmentPrimAndInstance(int segment) { return drawnPrims[segmentSlot[segment]].xy; }
int segmentMaterial(int segment) { return drawnPrims[segmentSlot[segment]].z; }
// What the fragments of a segment carry: (primId, elementId, material, segment).
ivec4 segmentIds(int segment) {
    return ivec4(segmentPrimAndInstance(segment).x, segmentCurve[segment], segmentMaterial(segment), segment);
}
