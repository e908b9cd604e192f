// The hair density volume (hdHair/curves/HairDensityGrid.h): σ per voxel,
// trilinear between voxel centres, and the optical depth along a ray
// through it, marched as the CPU's opticalDepth marches it. Needs
// shadows.glsl's ShadowUniforms (volumeOrigin, volume) and lights.glsl.
layout(binding = 8) uniform sampler3D hairDensity;

// Whether light i of the pass is shadowed through the volume (volume.x's bit i).
bool densityVolumeLight(int i) { return ((shadows.volume.x >> i) & 1) != 0; }

// The part [enter, leave] of the ray from + direction * [enter, leave]
// that lies inside the grid (slab test); false where none does.
bool densityRayInterval(vec3 from, vec3 direction, inout float enter, inout float leave) {
    vec3 low = shadows.volumeOrigin.xyz, high = low + shadows.volumeOrigin.w * vec3(shadows.volume.yzw);
    for (int axis = 0; axis < 3; ++axis) {
        if (direction[axis] == 0.0) {
            if (from[axis] < low[axis] || from[axis] > high[axis]) return false;
            continue;
        }
        float a = (low[axis] - from[axis]) / direction[axis], b = (high[axis] - from[axis]) / direction[axis];
        enter = max(enter, min(a, b));
        leave = min(leave, max(a, b));
    }
    return leave > enter;
}

// σ at a world point, from mip level `level` (0: the voxels themselves).
float densityAt(vec3 point, float level) {
    vec3 extent = shadows.volumeOrigin.w * vec3(shadows.volume.yzw);
    return textureLod(hairDensity, (point - shadows.volumeOrigin.xyz) / extent, level).r;
}

// ∫ σ ds from `from` to `to`: the part inside the grid, in steps of half a
// voxel, each step's σ at its middle.
float densityOpticalDepth(vec3 from, vec3 to) {
    float voxel = shadows.volumeOrigin.w;
    vec3 direction = to - from;
    float enter = 0.0, leave = 1.0;
    if (!densityRayInterval(from, direction, enter, leave)) return 0.0;
    float distance = (leave - enter) * length(direction);
    if (!(distance > 0.0)) return 0.0;
    // At most the grid's diagonal in half voxels (2 sqrt(3) 130 < 512).
    int steps = clamp(int(ceil(distance / (0.5 * voxel))), 1, 512);
    float step = distance / float(steps);
    float depth = 0.0;
    for (int k = 0; k < steps; ++k)
        depth += step * densityAt(from + direction * (enter + (leave - enter) * ((float(k) + 0.5) / float(steps))), 0.0);
    return depth;
}

// A fibre's own density lies around it, spread by the splat and the lookup
// over two voxels either side (a cubic B-spline in voxels), and would
// shadow the fibre itself: a march from a fibre starts one voxel out, past
// all but 1/24 of it. The first voxel it skips holds its neighbours'
// density too: this is that voxel's depth, taken as the density half a
// voxel further on, where 1/48 of a fibre's own is left, so a point deep in
// the hair is not lit as if a voxel of hair beside it were missing.
float densitySkippedVoxelDepth(vec3 point, vec3 direction) {
    float voxel = shadows.volumeOrigin.w;
    vec3 at = (point + direction * (1.5 * voxel) - shadows.volumeOrigin.xyz) / (voxel * vec3(shadows.volume.yzw));
    if (any(lessThan(at, vec3(0.0))) || any(greaterThan(at, vec3(1.0)))) return 0.0;
    return voxel * textureLod(hairDensity, at, 0.0).r;
}

// ∫ σ ds from `point` along the unit `direction` out of the grid through a
// cone that widens as tanHalfAngle (voxel cone tracing, Crassin et al.
// 2011): a step is as long as the cone's radius there and reads a mip level
// whose texels are half that radius wide, so a march across the grid takes
// tens of steps, not hundreds. The fibre at `point` must not shadow itself,
// and a wide fibre's own density (its whole α w L in the voxels around its
// centre line) would: the splat puts it in voxel centres within a voxel of
// the line, and a trilinear lookup reads centres within a texel of where it
// looks, so the march begins two voxels out, and texels of half the radius
// keep every lookup more than a voxel from the line for cones up to 45°.
// What lies between one and two voxels out is left out with it. It stops
// once k ∫ σ passes `enough`, where what follows no longer shows.
float densityConeDepth(vec3 point, vec3 direction, float tanHalfAngle, float enough) {
    float voxel = shadows.volumeOrigin.w;
    float start = 2.0 * voxel, enter = start, leave = voxel * (2.0 + length(vec3(shadows.volume.yzw)));
    if (!densityRayInterval(point, direction, enter, leave)) return 0.0;
    float maxLevel = float(textureQueryLevels(hairDensity) - 1);
    float depth = 0.0, s = enter;
    for (int k = 0; k < 256 && s < leave; ++k) {
        float radius = 0.5 * voxel + (s - start) * tanHalfAngle;
        float step = min(radius, leave - s);
        depth += step * densityAt(point + direction * (s + 0.5 * step), clamp(log2(radius / voxel) - 1.0, 0.0, maxLevel));
        s += step;
        if (shadows.extinction.x * depth > enough) break;
    }
    return depth;
}

// The fraction of light i that the hair lets through to `point` along the
// ray to the light (to its position, or out of the grid toward a distant
// one), T = exp(-k ∫σ ds), the deep opacity maps' k; the march starts a
// voxel out (densitySkippedVoxelDepth).
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
    return exp(-shadows.extinction.x * (depth + densitySkippedVoxelDepth(point, direction)));
}

// The share of the light going on past `point` along the unit `away` that
// the hair behind intercepts, 1 - exp(-k ∫σ) over a cone behind it out of
// the grid: dual scattering's d_b assumes a whole groom there (1), which a
// lone fibre (0) and a sparse tuft do not have. The cone's half-angle is the
// caller's: the spread about the line behind within which the light comes
// back.
float densityVolumeBackOccupancy(vec3 point, vec3 away, float tanHalfAngle) {
    const float saturated = 7.0;  // 1 - e^-7 = 0.999
    return 1.0 - exp(-shadows.extinction.x * densityConeDepth(point, away, tanHalfAngle, saturated));
}

// What SRBF lobe i (srbfLighting.glsl: radiance ∝ exp(λ (cos θ - 1)) about
// its centre) lets through to `point`: the march along the lobe's centre as
// a cone of the lobe's solid angle, 2π/λ = 2π (1 - cos α), so the lookup
// averages the hair over the directions the lobe's light comes from rather
// than along its centre alone (Ren et al. 2010 widen their map lookups for
// the same reason). Cones wider than 45° are held at 45°: one march stands
// for them poorly, and a lobe that wide is nearly the whole sky.
float densityVolumeLobeTransmittance(int i, vec3 point) {
    vec3 direction = normalize(lights.lightVector[i].xyz);
    float cosHalfAngle = max(1.0 - 1.0 / max(lights.lightScale[i].w, 1e-3), 0.70710678);
    float tanHalfAngle = sqrt(max(1.0 - cosHalfAngle * cosHalfAngle, 0.0)) / cosHalfAngle;
    return exp(-shadows.extinction.x * densityConeDepth(point, direction, tanHalfAngle, 1e30));
}

// What of a uniform dome reaches a fibre at `point` with unit tangent `t`
// through the hair: the transmittance of six cones of 45° about the axes,
// which cover seven eighths of the sphere (6 · 2π (1 - cos 45°) = 11.0 sr of
// 4π), as Unreal Engine 5's groom renderer traces its environment occlusion
// through the voxelised strands. Each cone is weighted by the light a fibre
// takes from its direction, its projected width |sin| to the tangent (the
// cos θ_i of the irradiance): light along the fibre barely reaches it, and
// along its own length the volume holds the fibre itself (its density is
// isotropic: a ray along fibres meets less than it says).
float densityVolumeDomeVisibility(vec3 point, vec3 t) {
    const vec3 axes[6] = vec3[6](vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0), vec3(0, 0, 1),
                                 vec3(0, 0, -1));
    float visible = 0.0, weights = 0.0;
    for (int j = 0; j < 6; ++j) {
        float weight = sqrt(max(1.0 - dot(t, axes[j]) * dot(t, axes[j]), 0.0));
        if (weight < 1e-3) continue;
        visible += weight * exp(-shadows.extinction.x * densityConeDepth(point, axes[j], 1.0, 12.0));
        weights += weight;
    }
    return weights > 0.0 ? visible / weights : 1.0;
}
