#version 450 core
#extension GL_GOOGLE_include_directive : require
// The display transform on the GPU (hdHair/gl/DisplayTransformPass.h): each
// pixel of the frame's pre-multiplied scene-linear colour, un-premultiplied
// for formats that keep alpha or taken over black for those that do not,
// through hdhairDisplay().
#include "include/displayFunction.glsl"

layout(binding = 0) uniform sampler2D linearColor;
uniform int overBlack;

layout(location = 0) out vec4 outColor;

void main() {
    vec4 color = texelFetch(linearColor, ivec2(gl_FragCoord.xy), 0);
    if (overBlack != 0) {
        color.a = 1.0;
    } else if (color.a > 0.0) {
        color.rgb /= color.a;
    }
    outColor = hdhairDisplay(color);
}
