#version 450 core
#extension GL_GOOGLE_include_directive : require
// Each segment of a span's centre-line polyline (strand.tese) becomes a
// camera-facing quad, two triangles: its ends are the tessellated points
// offset half the drawn width to either side.
#include "include/frameUniforms.glsl"
#include "include/shadingFeatures.glsl"

layout(lines) in;
layout(triangle_strip, max_vertices = 4) out;

layout(location = 0) in vec3 tesCentre[];
layout(location = 1) in vec3 tesAcross[];
layout(location = 2) in vec3 tesTangent[];
layout(location = 3) in vec4 tesColorAlpha[];
layout(location = 4) flat in ivec4 tesIds[];
layout(location = 5) in float tesSpanU[];

layout(location = 0) out vec3 worldPosition;
layout(location = 1) out vec3 worldTangent;
layout(location = 2) out vec4 colorAlpha;  // displayColor, opacity x coverage
layout(location = 3) flat out ivec4 ids;   // primId, elementId, material, segment
layout(location = 4) out float spanU;      // where on the span: per-point hair parameters
layout(location = 5) out vec3 strandCentre;  // the centre line under this point: where shadows are looked up
#ifdef HDHAIR_VERTEX_SHADOWS
layout(location = 6) in vec4 tesTransmittance[][HDHAIR_VERTEX_SHADOW_VECTORS];
layout(location = 6) out vec4 vertexTransmittance[HDHAIR_VERTEX_SHADOW_VECTORS];  // strandShading.glsl
#endif

void main() {
    for (int end = 0; end < 2; ++end) {
        for (int edge = 0; edge < 2; ++edge) {
            vec3 position = tesCentre[end] + tesAcross[end] * (float(edge) - 0.5);
            worldPosition = position;
            worldTangent = tesTangent[end];
            colorAlpha = tesColorAlpha[end];
            ids = tesIds[end];
            spanU = tesSpanU[end];
            strandCentre = tesCentre[end];
#ifdef HDHAIR_VERTEX_SHADOWS
            vertexTransmittance = tesTransmittance[end];
#endif
            gl_Position = frame.viewProjection * vec4(position, 1.0);
            EmitVertex();
        }
    }
    EndPrimitive();
}
