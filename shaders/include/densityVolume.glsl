// The hair density volume (hdHair/curves/HairDensityGrid.h): σ per voxel,
// trilinear between voxel centres, and the optical depth along a ray
// through it, marched as the CPU's opticalDepth marches it. Needs
// shadows.glsl's ShadowUniforms (volumeOrigin, volume) and lights.glsl.
layout(binding = 8) uniform sampler3D hairDensity;

// Whether light i of the pass is shadowed through the volume (volume.x's bit i).
bool densityVolumeLight(int i) { return ((shadows.volume.x >> i) & 1) != 0; }

// ∫ σ ds from `from` to `to`: the part inside the grid (slab test), in
// steps of half a voxel, each step's σ at its middle.
float densityOpticalDepth(vec3 from, vec3 to) {
    vec3 dims = vec3(shadows.volume.yzw);
    float voxel = shadows.volumeOrigin.w;
    vec3 low = shadows.volumeOrigin.xyz, high = low + voxel * dims;
    vec3 direction = to - from;
    float enter = 0.0, leave = 1.0;
    for (int axis = 0; axis < 3; ++axis) {
        if (direction[axis] == 0.0) {
            if (from[axis] < low[axis] || from[axis] > high[axis]) return 0.0;
            continue;
        }
        float a = (low[axis] - from[axis]) / direction[axis], b = (high[axis] - from[axis]) / direction[axis];
        enter = max(enter, min(a, b));
        leave = min(leave, max(a, b));
    }
    float distance = (leave - enter) * length(direction);
    if (!(distance > 0.0)) return 0.0;
    // At most the grid's diagonal in half voxels (2 sqrt(3) 130 < 512).
    int steps = clamp(int(ceil(distance / (0.5 * voxel))), 1, 512);
    float step = distance / float(steps);
    float depth = 0.0;
    for (int k = 0; k < steps; ++k) {
        vec3 at = from + direction * (enter + (leave - enter) * ((float(k) + 0.5) / float(steps)));
        depth += step * texture(hairDensity, (at - low) / (voxel * dims)).r;
    }
    return depth;
}

// The fraction of light i that the hair lets through to `point` along the
// ray to the light (to its position, or out of the grid toward a distant
// one), T = exp(-k ∫σ ds), the deep opacity maps' k. A fibre's own density
// lies around it, spread by the splat and the lookup over two voxels either
// side (a cubic B-spline in voxels), and would shadow the fibre itself: the
// march starts one voxel toward the light, past all but 1/24 of it. The
// first voxel it skips holds its neighbours' density too: that is taken as
// the density half a voxel further on, where 1/48 of a fibre's own is left,
// so a point deep in the hair is not lit as if a voxel of hair in front of
// it were missing.
float densityVolumeTransmittance(int i, vec3 point) {
    vec4 light = lights.lightVector[i];
    bool local = light.w > 0.5 && light.w < 1.5;  // kind 1; distant 0 and SRBF lobes 2 are directions
    vec3 toLight = local ? light.xyz - point : light.xyz;
    float distance = length(toLight);
    if (!(distance > 0.0)) return 1.0;  // a light exactly on the point
    vec3 direction = toLight / distance;
    float voxel = shadows.volumeOrigin.w;
    float reach = local ? distance : voxel * length(vec3(shadows.volume.yzw));
    if (reach <= voxel) return 1.0;  // the light within a voxel: nothing between
    float depth = densityOpticalDepth(point + direction * voxel, point + direction * (local ? distance : voxel + reach));
    vec3 dims = vec3(shadows.volume.yzw);
    vec3 skipped = (point + direction * (1.5 * voxel) - shadows.volumeOrigin.xyz) / (voxel * dims);
    if (all(greaterThanEqual(skipped, vec3(0.0))) && all(lessThanEqual(skipped, vec3(1.0))))
        depth += voxel * texture(hairDensity, skipped).r;
    return exp(-shadows.extinction.x * depth);
}
