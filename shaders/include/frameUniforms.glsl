// Per-frame camera, tessellation and coverage parameters
// (hdHair/gl/UniformBlocks.h FrameUniforms mirrors this block).
layout(std140, binding = 0) uniform FrameUniforms {
    mat4 viewProjection;
    vec4 cameraPosition;      // world space; w = 1 perspective, 0 orthographic
    vec4 cameraForward;       // world-space viewing direction
    vec2 viewportSize;        // pixels
    float pixelsPerSegment;   // projectedLength: target on-screen length of one tessellated segment
    float maxSegmentsPerSpan; // upper bound per Catmull-Rom span
    // Pixels one world unit spans at clip w = 1 (horizontal): a width w at
    // clip depth c.w covers w * pixelsPerUnit / c.w pixels.
    float pixelsPerUnit;
    // Strands projecting thinner than this many pixels are drawn this wide
    // with their alpha scaled by true / drawn width (0: true widths, opaque).
    float minPixelWidth;
    int drawMode;             // 0: opaque, 1: pre-multiplied alpha, 2: ids only (the ids pass)
    int orderedDraw;          // 1: patches are read through the draw-order buffer
    // Blended frames: a pixel's depth and ids belong to its nearest strand
    // fragment whose alpha (coverage x opacity) is at least this
    // (hdHair/plan/NearestStrandRule.h).
    float nearestStrandMinAlpha;
    // screenError tessellation: the most a strand's centre line may stray
    // from its curve, in this pass's pixels (a light view's texels); 0:
    // projectedLength, one segment every pixelsPerSegment pixels.
    float tessellationTolerance;
    // From the rendering space back to linear Rec.709: screenError
    // tessellation measures colour as authored, whatever renderingSpace.
    mat3 colorToRec709;
    // Vertex shadows: the longest a segment may be, world units, in the
    // camera's passes (strand.tesc); 0: no limit (and in the light views).
    float shadowSegmentLength;
} frame;

// Whether a blended fragment of this alpha may give its pixel depth and ids.
bool definesDepthAndIds(float alpha) {
    return alpha >= frame.nearestStrandMinAlpha;
}

// Direction from a world-space point towards the eye.
vec3 directionToEye(vec3 worldPosition) {
    if (frame.cameraPosition.w > 0.5) return normalize(frame.cameraPosition.xyz - worldPosition);
    return -frame.cameraForward.xyz;
}
