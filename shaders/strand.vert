#version 450 core
// Passes each Catmull-Rom control point (hdHair/curves/PreparedCurves.h) on
// to the tessellation stages; all geometry work happens there.
layout(location = 0) in vec3 position;
layout(location = 1) in float width;
layout(location = 2) in vec3 color;
layout(location = 3) in float opacity;

layout(location = 0) out vec4 vsPositionWidth;
layout(location = 1) out vec4 vsColorOpacity;

void main() {
    vsPositionWidth = vec4(position, width);
    vsColorOpacity = vec4(color, opacity);
}
