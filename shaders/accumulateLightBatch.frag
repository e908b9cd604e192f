#version 450 core
// Adds one light batch's frame to the frame so far (Svoboda 2012, section
// 2.5.3): every batch draws the same strands in the same order with the same
// coverage, so their alphas are equal and their pre-multiplied colours add
// up to the frame lit by all lights at once. The blend state keeps the
// destination's alpha (ONE, ONE for colour; ZERO, ONE for alpha).
layout(binding = 0) uniform sampler2D batchColor;
layout(location = 0) out vec4 outColor;

void main() {
    outColor = texelFetch(batchColor, ivec2(gl_FragCoord.xy), 0);
}
