// Per-frame camera and tessellation parameters (hdHair/gl/StrandPass.cpp fills them).
layout(std140, binding = 0) uniform FrameUniforms {
    mat4 viewProjection;
    vec4 cameraPosition;      // world space; w = 1 perspective, 0 orthographic
    vec4 cameraForward;       // world-space viewing direction
    vec2 viewportSize;        // pixels
    float pixelsPerSegment;   // target on-screen length of one tessellated segment
    float maxSegmentsPerSpan; // upper bound per Catmull-Rom span
} frame;

// Direction from a world-space point towards the eye.
vec3 directionToEye(vec3 worldPosition) {
    if (frame.cameraPosition.w > 0.5) return normalize(frame.cameraPosition.xyz - worldPosition);
    return -frame.cameraForward.xyz;
}
