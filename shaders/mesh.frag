#version 450 core
#extension GL_GOOGLE_include_directive : require
// Meshes as opaque occluders: Lambert under the pass's lights (the same
// lights, units and 1/pi convention as the hair: a Kajiya-Kay fibre lit
// head-on reflects like this surface of the same albedo), or displayColor
// unlit. Depth is written and tested like any opaque geometry, so strands
// behind a mesh are hidden on every transparency path; the ids and the
// nearest depth name the mesh where it is the nearest thing
// (hdHair/plan/NearestStrandRule.h).
// Meshes are two-sided: no face is culled, and a face seen from the back is
// lit as its back (the normal reversed). They receive the hair's shadows
// (the deep opacity maps of the batch's lights) and the meshes' own, each
// other's and their own (shadows.glsl meshShadowTransmittance).
#include "include/shadingFeatures.glsl"
#include "include/lights.glsl"
#include "include/meshGeometry.glsl"
#include "include/shadowFragmentLists.glsl"
#include "include/shadows.glsl"

layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec3 worldNormal;
layout(location = 2) in vec3 color;
layout(location = 3) flat in int face;

layout(location = 1) uniform ivec2 primAndInstance;
layout(location = 2) uniform int lit;  // 1: Lambert; 0: displayColor unlit

layout(location = 0) out vec4 outColor;
layout(location = 1) out int outPrimId;
layout(location = 2) out int outInstanceId;
layout(location = 3) out int outElementId;
layout(location = 4) out float outNearestDepth;  // hdHair/gl/RenderTarget.h kNearestDepthOutput

void main() {
    vec3 radiance;
    if (lit != 0) {
        vec3 n = normalize(worldNormal);
        if (!gl_FrontFacing) n = -n;
        const float inversePi = 0.31830988618379067;
        radiance = lights.ambient.rgb * color;
        for (int i = 0; i < lights.lightCount.x; ++i) {
            vec3 l;
            vec3 irradiance = lightIrradiance(i, worldPosition, l);
            if (all(equal(irradiance, vec3(0.0)))) continue;  // unlit here: no shadow lookup
            irradiance *= meshShadowTransmittance(i, worldPosition, n);
            radiance += irradiance * (max(dot(n, l), 0.0) * inversePi) * color;
        }
    } else {
        // Unlit colour belongs to the first light batch only, so that
        // summing batches counts it once.
        radiance = lights.lightCount.y == 0 ? color : vec3(0.0);
    }
    outColor = vec4(radiance, 1.0);
    outPrimId = primAndInstance.x;
    outInstanceId = primAndInstance.y;
    outElementId = face;
    outNearestDepth = gl_FragCoord.z;
}
