#version 450 core
#extension GL_GOOGLE_include_directive : require
// Not drawn: a stage that includes marschner.glsl and calls it, so that
// testShaders validates the include with glslangValidator until strand.frag
// uses it.
#include "include/marschner.glsl"

layout(binding = 5) uniform sampler2DArray marschnerTables;
layout(location = 0) uniform vec3 marschnerAlpha;
layout(location = 1) uniform vec3 marschnerBeta;

layout(location = 0) in vec3 worldTangent;
layout(location = 1) in vec3 toLight;
layout(location = 2) in vec3 toEye;
layout(location = 0) out vec4 outColor;

void main() {
    outColor = vec4(marschnerTabled(worldTangent, toLight, toEye, marschnerTables, marschnerAlpha, marschnerBeta), 1.0);
}
