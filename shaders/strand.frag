#version 450 core
#extension GL_GOOGLE_include_directive : require
// Kajiya-Kay shading of opaque strands: displayColor is the fibre colour,
// lit by every light of the stage plus the dome light's ambient term.
#include "include/frameUniforms.glsl"
#include "include/lights.glsl"
#include "include/kajiyaKay.glsl"

layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec3 worldTangent;
layout(location = 2) in vec4 colorOpacity;
layout(location = 3) flat in int elementId;

// x: the prim's id (Hydra's primId), y: first segment of the draw (unused here).
layout(location = 0) uniform ivec2 drawIds;

layout(location = 0) out vec4 outColor;
// Picking and selection outputs; the render target binds them only when a
// host asks for them (otherwise these writes go nowhere and cost nothing).
layout(location = 1) out int outPrimId;
layout(location = 2) out int outInstanceId;
layout(location = 3) out int outElementId;

void main() {
    vec3 t = normalize(worldTangent);
    vec3 e = directionToEye(worldPosition);
    vec3 hairColor = colorOpacity.rgb;
    vec3 radiance = lights.ambient.rgb * hairColor;
    vec3 kk = lights.kajiyaKayParameters.xyz;
    for (int i = 0; i < lights.lightCount.x; ++i) {
        vec3 l;
        vec3 irradiance = lightIrradiance(i, worldPosition, l);
        KajiyaKayTerms terms = kajiyaKay(t, l, e, kk.x, kk.y, kk.z);
        radiance += irradiance * (terms.diffuse * hairColor + terms.specular);
    }
    // Opaque strands for now: alpha is coverage, which is 1 inside the ribbon.
    outColor = vec4(radiance, 1.0);
    outPrimId = drawIds.x;
    outInstanceId = 0;  // curves are not instanced yet: instance 0 of the prim
    outElementId = elementId;
}
