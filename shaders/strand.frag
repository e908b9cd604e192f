#version 450 core
#extension GL_GOOGLE_include_directive : require
// Strands drawn straight into the frame: opaque (alpha 1, depth written) or
// pre-multiplied (colour x alpha, alpha; blended ONE, ONE_MINUS_SRC_ALPHA
// over what is behind, in the order the draw-order buffer gives). Blended
// draws also give the frame its depth, whatever their order: the nearest-
// depth image is min-blended, so it keeps the nearest fragment that
// definesDepthAndIds() accepts.
#include "include/shadingFeatures.glsl"
#include "include/frameUniforms.glsl"
#include "include/lights.glsl"
#include "include/kajiyaKay.glsl"
#include "include/marschner.glsl"
#include "include/marschnerAnalytic.glsl"
#include "include/dualScattering.glsl"
#include "include/catmullRom.glsl"
#include "include/strandGeometry.glsl"
#include "include/hairMaterials.glsl"
#include "include/shadowFragmentLists.glsl"
#include "include/shadows.glsl"
#include "include/srbfLighting.glsl"
#include "include/strandShading.glsl"

layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec3 worldTangent;
layout(location = 2) in vec4 colorAlpha;
layout(location = 3) flat in ivec4 ids;  // primId, elementId, material, segment
layout(location = 4) in float spanU;
layout(location = 5) in vec3 strandCentre;

layout(location = 0) out vec4 outColor;
// Picking and selection outputs; the render target binds them only when a
// host asks for them (otherwise these writes go nowhere and cost nothing).
layout(location = 1) out int outPrimId;
layout(location = 2) out int outInstanceId;
layout(location = 3) out int outElementId;
// Blended frames only (hdHair/gl/RenderTarget.h kNearestDepthOutput): this
// fragment's window depth if it may define the pixel's depth, else 1 (the
// clear value), which the min blend ignores.
layout(location = 4) out float outNearestDepth;

void main() {
    // Nothing to add: not even an id (opacity 0 strands produce nothing).
    if (frame.drawMode != 0 && colorAlpha.a <= 0.0) discard;
    // The ids pass under transparency keeps the fragment the depth comes
    // from: the nearest one faint fragments are looked through to.
    bool definesDepth = frame.drawMode == 0 || definesDepthAndIds(colorAlpha.a);
    if (frame.drawMode == 2 && !definesDepth) discard;
#if HDHAIR_FEATURE_SHADE
    if (frame.drawMode == 2) {
        outColor = vec4(0.0);  // masked: the ids pass needs no shading
    } else {
        vec3 radiance =
            strandRadiance(worldPosition, strandCentre, worldTangent, colorAlpha.rgb, ids.z, ids.w, spanU);
        outColor = frame.drawMode == 0 ? vec4(radiance, 1.0) : vec4(radiance * colorAlpha.a, colorAlpha.a);
    }
#else
    outColor = vec4(0.0);  // the ids pass's program: no shading compiled
#endif
    outPrimId = ids.x;
    outInstanceId = segmentPrimAndInstance(ids.w).y;
    outElementId = ids.y;
    outNearestDepth = definesDepth ? gl_FragCoord.z : 1.0;
}
