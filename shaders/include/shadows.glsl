// How much of each light of a pass reaches a strand: the transmittance of
// the hair in front of it, from deep opacity maps (Yuksel & Keyser 2008, as
// Svoboda 2012 section 2.7 implemented them) or, with shadowMode=reference,
// from every fragment the light view saw. hdHair/plan/DeepOpacityLayers.h
// gives the layers, the lookup and k; hdHair/gl/UniformBlocks.h
// ShadowUniforms mirrors the block. Needs lights.glsl (HDHAIR_MAX_LIGHTS)
// and shadowFragmentLists.glsl, after shadingFeatures.glsl.
#define HDHAIR_SHADOW_OFF 0
#define HDHAIR_SHADOW_DEEP_OPACITY 1
#define HDHAIR_SHADOW_REFERENCE 2
// The depth pass's clear value: no hair in this texel.
#define HDHAIR_NO_HAIR 3.0e38

layout(std140, binding = 2) uniform ShadowUniforms {
    mat4 lightViewProjection[HDHAIR_MAX_LIGHTS];  // world to the light view's clip space
    vec4 lightEye[HDHAIR_MAX_LIGHTS];              // xyz: the light view's eye
    vec4 lightForward[HDHAIR_MAX_LIGHTS];          // xyz: its unit viewing direction
    // x: the map's slot (-1: no shadow from this light), y: d_K (world units),
    // z: a texel's world size (at linear depth 1 when perspective),
    // w: 1 perspective, 0 orthographic.
    vec4 lightMap[HDHAIR_MAX_LIGHTS];
    vec4 layerBoundaries[8];  // d_k / d_K for layers k = 1..32, 4 a vec4
    ivec4 mode;               // x: HDHAIR_SHADOW_*, y: layers, z: 0 nearest, 1 bilinear; w: resolution
    vec4 extinction;          // x: k of T = exp(-k opacity)
    ivec4 occluders;          // x: 1 when shadowMeshDepths holds the meshes of every slot;
                              // y: 1 when SRBF lights read shadowOpacity's mip chain;
                              // z: 1 when dual scattering reads the hair behind a fibre
                              // from the density volume (strandShading.glsl); w: 1 when
                              // the uniform dome reaches strands through the volume
    // The view each light's mesh depth is drawn from, fitted to the hair and
    // the meshes together (hdHair/plan/ShadowPlanner.h PlannedShadow::meshView).
    mat4 meshViewProjection[HDHAIR_MAX_LIGHTS];
    vec4 meshEye[HDHAIR_MAX_LIGHTS];      // xyz: its eye
    vec4 meshForward[HDHAIR_MAX_LIGHTS];  // xyz: its unit viewing direction
    // x: the slot of its mesh depth (-1: none), y: a texel's world size (at
    // linear depth 1 when perspective), z: 1 perspective, 0 orthographic,
    // w: 1 the light's own view, 0 borrowed (an SRBF lobe reading another's).
    vec4 meshMap[HDHAIR_MAX_LIGHTS];
    // The hair density volume (densityVolume.glsl): xyz its lowest corner, w
    // a voxel's edge; x: a bit per light of the pass shadowed through it,
    // yzw: its voxels along x, y, z.
    vec4 volumeOrigin;
    ivec4 volume;
} shadows;

// Per light slot: the nearest hair's linear depth, and the layers, 4 a texel
// of RGBA16F, ceil(layers / 4) array layers a slot.
layout(binding = 2) uniform sampler2DArray shadowDepths;
layout(binding = 3) uniform sampler2DArray shadowOpacity;
// Per light slot: the nearest mesh's linear depth (R32F; HDHAIR_NO_HAIR
// where there is none). Meshes are opaque: what lies behind gets no light.
layout(binding = 4) uniform sampler2DArray shadowMeshDepths;

#include "include/densityVolume.glsl"

// Linear depth in light i's view: world units along its viewing direction.
float shadowLinearDepth(int i, vec3 position) {
    return dot(position - shadows.lightEye[i].xyz, shadows.lightForward[i].xyz);
}

int shadowSlot(int i) { return int(shadows.lightMap[i].x); }

// Linear depth in light i's mesh view (shadowMeshDepths' depth).
float meshLinearDepth(int i, vec3 position) {
    return dot(position - shadows.meshEye[i].xyz, shadows.meshForward[i].xyz);
}

// A texel's world size at linear depth z in light i's mesh view.
float meshTexelSize(int i, float z) { return shadows.meshMap[i].y * (shadows.meshMap[i].z > 0.5 ? max(z, 0.0) : 1.0); }

// The fraction of light i that the meshes let through to `point`: the share
// of the four mesh-view texels around it (bilinear weights, percentage-closer
// filtering) whose nearest mesh lies beyond it, less `biasTexels` of the
// view's texels so that a surface does not shadow itself where its own depth
// was rasterised at a texel centre a little nearer. 1 without a mesh map.
float meshTransmittance(int i, vec3 point, float biasTexels) {
#if HDHAIR_FEATURE_MESH_OCCLUDERS
    if (shadows.occluders.x == 0 || shadows.meshMap[i].x < 0.0) return 1.0;
    vec4 clip = shadows.meshViewProjection[i] * vec4(point, 1.0);
    if (clip.w <= 0.0) return 1.0;  // behind a perspective light's eye: outside its view
    float z = meshLinearDepth(i, point);
    z -= biasTexels * meshTexelSize(i, z);
    vec2 corner = (clip.xy / clip.w * 0.5 + 0.5) * float(shadows.mode.w) - 0.5;
    ivec2 base = ivec2(floor(corner));
    vec2 w = corner - vec2(base);
    vec4 lit;  // texels (0,0), (1,0), (0,1), (1,1) from base: 1 where no mesh is nearer
    for (int t = 0; t < 4; ++t) {
        ivec2 texel = base + ivec2(t & 1, t >> 1);
        bool inside = all(greaterThanEqual(texel, ivec2(0))) && all(lessThan(texel, ivec2(shadows.mode.w)));
        lit[t] = !inside || z <= texelFetch(shadowMeshDepths, ivec3(texel, int(shadows.meshMap[i].x)), 0).r ? 1.0 : 0.0;
    }
    return mix(mix(lit.x, lit.y, w.x), mix(lit.z, lit.w, w.x), w.y);
#else
    return 1.0;
#endif
}

float shadowLayerBoundary(int layer) { return shadows.layerBoundaries[layer / 4][layer % 4]; }

// The layer count (mode.y) and the vec4s holding the layers: constants in a
// program specialised for its frame (HDHAIR_SHADOW_LAYERS, written by
// hdHair/gl/ShadingFeatures.h), so that up to 4 layers take the straight
// code below, in registers; the uniform, and room for 32 layers, otherwise.
#ifdef HDHAIR_SHADOW_LAYERS
int shadowLayerCount() { return HDHAIR_SHADOW_LAYERS; }
#define HDHAIR_SHADOW_LAYER_VECTORS ((HDHAIR_SHADOW_LAYERS + 3) / 4)
#else
int shadowLayerCount() { return shadows.mode.y; }
#define HDHAIR_SHADOW_LAYER_VECTORS 8
#endif

// Opacity at depth d (> 0) behind the nearest hair, from the layers'
// opacities (4 a vec4, up to 32): linear between layers, the last layer's
// beyond it. `scale`: d_K, the last layer's depth (lightMap.y).
float opacityBehindNearestHair(float d, float scale, vec4 targets[HDHAIR_SHADOW_LAYER_VECTORS]) {
    float previousDepth = 0.0, previousOpacity = 0.0;
    for (int layer = 0; layer < shadowLayerCount(); ++layer) {
        float boundary = shadowLayerBoundary(layer) * scale;
        float opacity = targets[layer / 4][layer % 4];
        if (d < boundary)
            return mix(previousOpacity, opacity, (d - previousDepth) / max(boundary - previousDepth, 1e-30));
        previousDepth = boundary;
        previousOpacity = opacity;
    }
    return previousOpacity;
}

#if HDHAIR_SHADOW_LAYER_VECTORS == 1
// The same for at most 4 layers in one vec4 (a specialised program), as
// straight code: no array, whose indexing goes through memory, and no loop.
// Layers are tried from the last to the first, so the first whose boundary
// lies beyond d is the one kept; the arithmetic is the loop's above.
float opacityBehindNearestHair(float d, float scale, vec4 layers) {
    vec4 boundaries = shadows.layerBoundaries[0] * scale;
    float opacity = layers[HDHAIR_SHADOW_LAYERS - 1];
#if HDHAIR_SHADOW_LAYERS > 3
    if (d < boundaries.w) opacity = mix(layers.z, layers.w, (d - boundaries.z) / max(boundaries.w - boundaries.z, 1e-30));
#endif
#if HDHAIR_SHADOW_LAYERS > 2
    if (d < boundaries.z) opacity = mix(layers.y, layers.z, (d - boundaries.y) / max(boundaries.z - boundaries.y, 1e-30));
#endif
#if HDHAIR_SHADOW_LAYERS > 1
    if (d < boundaries.y) opacity = mix(layers.x, layers.y, (d - boundaries.x) / max(boundaries.y - boundaries.x, 1e-30));
#endif
    if (d < boundaries.x) opacity = mix(0.0, layers.x, (d - 0.0) / max(boundaries.x - 0.0, 1e-30));
    return opacity;
}
#endif

// Opacity in front of linear depth z at one texel of light i's deep opacity
// map: 0 in front of the nearest hair (or where there is none).
float deepOpacityAt(int i, ivec2 texel, float z) {
    int slot = shadowSlot(i);
    float d = z - texelFetch(shadowDepths, ivec3(texel, slot), 0).r;
    if (d <= 0.0) return 0.0;
#if HDHAIR_SHADOW_LAYER_VECTORS == 1
    return opacityBehindNearestHair(d, shadows.lightMap[i].y, texelFetch(shadowOpacity, ivec3(texel, slot), 0));
#else
    int targets = (shadowLayerCount() + 3) / 4;
    vec4 layers[HDHAIR_SHADOW_LAYER_VECTORS];
    for (int t = 0; t < targets; ++t) layers[t] = texelFetch(shadowOpacity, ivec3(texel, slot * targets + t), 0);
    return opacityBehindNearestHair(d, shadows.lightMap[i].y, layers);
#endif
}

// The convolution optical depth map of Ren et al. 2010 §5 (digest §4.3-4.4),
// with a mip chain where the paper builds summed-area tables: each layer's
// opacity (optical depth over k, T = exp(-k opacity)) averaged over the
// 2R-texel square around `position` (level log2 2R, trilinear), at depth d
// behind the nearest hair of the point's own texel (z0 cannot be averaged:
// the paper keeps it apart too), then exponentiated by the caller. Jensen:
// exp of the mean optical depth is at least the mean transmittance, so this
// is brighter than the nine taps where occlusion varies over the footprint.
float convolvedOpacityAt(int i, vec2 position, ivec2 texel, float z, float radius) {
    int slot = shadowSlot(i);
    float d = z - texelFetch(shadowDepths, ivec3(texel, slot), 0).r;
    if (d <= 0.0) return 0.0;
    float lod = log2(2.0 * radius);
    vec2 uv = position / float(shadows.mode.w);
#if HDHAIR_SHADOW_LAYER_VECTORS == 1
    return opacityBehindNearestHair(d, shadows.lightMap[i].y, textureLod(shadowOpacity, vec3(uv, float(slot)), lod));
#else
    int targets = (shadowLayerCount() + 3) / 4;
    vec4 layers[HDHAIR_SHADOW_LAYER_VECTORS];
    for (int t = 0; t < targets; ++t) layers[t] = textureLod(shadowOpacity, vec3(uv, float(slot * targets + t)), lod);
    return opacityBehindNearestHair(d, shadows.lightMap[i].y, layers);
#endif
}

// The reference: every fragment of the texel nearer than z, exactly what
// the layers approximate (so the strand's own fragments count too when they
// are nearer, as they do in the layers).
float referenceOpacityAt(int i, ivec2 texel, float z) {
    float opacity = 0.0;
    uint end = uint(HDHAIR_SHADOW_NODE_POOLS) * shadowPoolSize();
    for (uint node = imageLoad(shadowListHeads, ivec3(texel, shadowSlot(i))).r; node < end;) {
        ShadowNode fragment = readShadowNode(node);
        if (fragment.depth < z) opacity += fragment.alpha;
        node = fragment.next;
    }
    return opacity;
}

// The hair's transmittance at one texel of light i's map, at linear depth z.
float shadowTransmittanceAt(int i, ivec2 texel, float z) {
    if (any(lessThan(texel, ivec2(0))) || any(greaterThanEqual(texel, ivec2(shadows.mode.w)))) return 1.0;
#if HDHAIR_FEATURE_SHADOW_REFERENCE && HDHAIR_FEATURE_DEEP_OPACITY
    float opacity = shadows.mode.x == HDHAIR_SHADOW_REFERENCE ? referenceOpacityAt(i, texel, z)
                                                              : deepOpacityAt(i, texel, z);
#elif HDHAIR_FEATURE_SHADOW_REFERENCE
    float opacity = referenceOpacityAt(i, texel, z);
#else
    float opacity = deepOpacityAt(i, texel, z);
#endif
    return exp(-shadows.extinction.x * opacity);
}

#if HDHAIR_SHADOW_LAYER_VECTORS == 1 && !HDHAIR_FEATURE_SHADOW_REFERENCE
// opacityBehindNearestHair for four texels at once: the same arithmetic,
// lane by lane.
vec4 opacityBehindNearestHair(vec4 d, float scale, vec4 layer0, vec4 layer1, vec4 layer2, vec4 layer3) {
    vec4 boundaries = shadows.layerBoundaries[0] * scale;
    vec4 layers[4] = vec4[4](layer0, layer1, layer2, layer3);
    vec4 opacity = layers[HDHAIR_SHADOW_LAYERS - 1];
#if HDHAIR_SHADOW_LAYERS > 3
    opacity = mix(opacity, mix(layer2, layer3, (d - boundaries.z) / max(boundaries.w - boundaries.z, 1e-30)),
                  lessThan(d, vec4(boundaries.w)));
#endif
#if HDHAIR_SHADOW_LAYERS > 2
    opacity = mix(opacity, mix(layer1, layer2, (d - boundaries.y) / max(boundaries.z - boundaries.y, 1e-30)),
                  lessThan(d, vec4(boundaries.z)));
#endif
#if HDHAIR_SHADOW_LAYERS > 1
    opacity = mix(opacity, mix(layer0, layer1, (d - boundaries.x) / max(boundaries.y - boundaries.x, 1e-30)),
                  lessThan(d, vec4(boundaries.y)));
#endif
    opacity = mix(opacity, mix(vec4(0.0), layer0, (d - 0.0) / max(boundaries.x - 0.0, 1e-30)),
                  lessThan(d, vec4(boundaries.x)));
    return opacity;
}

// shadowTransmittanceAt (deep opacity maps) at the 2 x 2 texels from
// `base`, in textureGather's order: (0,1), (1,1), (1,0), (0,0). One gather
// fetches the four texels' nearest hair and one each layer, where the
// texel-by-texel lookup fetches 8 times (its bilinear filter is a third of
// the bear's strand pass on llvmpipe); the values and arithmetic are the
// same. Gathered at the corner the four texels share, where the gather's
// footprint is exactly them whatever its rounding; texels off the map,
// which the edge clamp repeats, get no shadow.
vec4 gatheredTransmittances(int i, ivec2 base, float z) {
    float slot = float(shadowSlot(i));
    vec3 at = vec3(vec2(base + 1) / float(shadows.mode.w), slot);
    ivec4 x = base.x + ivec4(0, 1, 1, 0), y = base.y + ivec4(1, 1, 0, 0);
    int last = shadows.mode.w - 1;
    bvec4 outside = greaterThan(ivec4(notEqual(clamp(x, 0, last), x)) + ivec4(notEqual(clamp(y, 0, last), y)), ivec4(0));
    vec4 d = z - textureGather(shadowDepths, at, 0);
    vec4 layer0 = textureGather(shadowOpacity, at, 0);
    vec4 layer1 = HDHAIR_SHADOW_LAYERS > 1 ? textureGather(shadowOpacity, at, 1) : vec4(0.0);
    vec4 layer2 = HDHAIR_SHADOW_LAYERS > 2 ? textureGather(shadowOpacity, at, 2) : vec4(0.0);
    vec4 layer3 = HDHAIR_SHADOW_LAYERS > 3 ? textureGather(shadowOpacity, at, 3) : vec4(0.0);
    vec4 opacity = opacityBehindNearestHair(d, shadows.lightMap[i].y, layer0, layer1, layer2, layer3);
    opacity = mix(opacity, vec4(0.0), lessThanEqual(d, vec4(0.0)));
    vec4 transmittance = exp(-shadows.extinction.x * opacity);
    return mix(transmittance, vec4(1.0), outside);
}
#endif

// The fraction of light i that the hair lets through to `point`: a point
// on a strand's centre line or on a mesh. Bias: one texel's
// world size, so that where the camera's polyline and the light's (each
// within its view's tessellation tolerance of the curve, a fraction of a
// pixel or texel) and the light's rasterisation of the same strand disagree
// by less than a texel, the strand does not shadow itself.
float hairShadowTransmittance(int i, vec3 point) {
#if HDHAIR_FEATURE_DENSITY_VOLUME
    if (densityVolumeLight(i)) return densityVolumeTransmittance(i, point);
#endif
#if !HDHAIR_FEATURE_DEEP_OPACITY && !HDHAIR_FEATURE_SHADOW_REFERENCE
    return 1.0;  // shadows off, or no light of the pass has a map
#else
    if (shadows.mode.x == HDHAIR_SHADOW_OFF || shadows.lightMap[i].x < 0.0) return 1.0;
    vec4 clip = shadows.lightViewProjection[i] * vec4(point, 1.0);
    if (clip.w <= 0.0) return 1.0;  // behind a perspective light's eye: outside its view
    vec2 position = (clip.xy / clip.w * 0.5 + 0.5) * float(shadows.mode.w);
    float z = shadowLinearDepth(i, point);
    z -= shadows.lightMap[i].z * (shadows.lightMap[i].w > 0.5 ? z : 1.0);
#if HDHAIR_FEATURE_BILINEAR_SHADOWS
    if (shadows.mode.z == 0) return shadowTransmittanceAt(i, ivec2(floor(position)), z);
    // Bilinear: the four nearest texels' transmittances, each against its
    // own nearest hair (z0-relative values cannot be filtered by the
    // hardware: thesis section 1.5.4), weighted by distance.
    vec2 corner = position - 0.5;
    ivec2 base = ivec2(floor(corner));
    vec2 w = corner - vec2(base);
#if HDHAIR_SHADOW_LAYER_VECTORS == 1 && !HDHAIR_FEATURE_SHADOW_REFERENCE
    vec4 t = gatheredTransmittances(i, base, z);  // (0,1), (1,1), (1,0), (0,0)
    return mix(mix(t.w, t.z, w.x), mix(t.x, t.y, w.x), w.y);
#else
    float t00 = shadowTransmittanceAt(i, base, z);
    float t10 = shadowTransmittanceAt(i, base + ivec2(1, 0), z);
    float t01 = shadowTransmittanceAt(i, base + ivec2(0, 1), z);
    float t11 = shadowTransmittanceAt(i, base + ivec2(1, 1), z);
    return mix(mix(t00, t10, w.x), mix(t01, t11, w.x), w.y);
#endif
#else
    return shadowTransmittanceAt(i, ivec2(floor(position)), z);  // shadowFilter=nearest
#endif
#endif
}

// What reaches a strand: through the hair and past the meshes (a texel's
// bias in the meshes' view, as in the hair's).
float shadowTransmittance(int i, vec3 centre) {
    return hairShadowTransmittance(i, centre) * meshTransmittance(i, centre, 1.0);
}

// What reaches a mesh: through the hair, and past the meshes, its own faces
// included. `normal`: the surface's, facing the light. The lookup point is
// moved 1.5 texels off the surface along it (normal-offset shadows): the
// depth of a surface at angle θ to the light changes by tan θ a texel, and
// the offset, 1.5/cos θ texels along the light, covers that over the two
// texels the filter reads, so a lit face does not shadow itself at any angle.
// A lobe that borrows another lobe's map (ShadowPlan::sharedMaps) sees the
// meshes from that lobe's direction, where a surface's own faces are not
// where they are along this one: meshes take only the hair's shadow from it.
float meshShadowTransmittance(int i, vec3 point, vec3 normal) {
    if (shadows.meshMap[i].w < 0.5) return hairShadowTransmittance(i, point);
    float texel = meshTexelSize(i, meshLinearDepth(i, point));
    return hairShadowTransmittance(i, point) * meshTransmittance(i, point + normal * (1.5 * texel), 1.0);
}

// What reaches a strand from SRBF light i (srbfLighting.glsl), whose
// directions spread about its centre: after Ren et al. 2010 §5 (digest §4.4),
// the lookup widens with depth behind the first hair, over a square of
// half-size R = (z − z0)/2 · tan α, α the lobe's 10⁻³ support
// (cos α = 1 − ln(1000)/λ), z0 the nearest hair at the point's texel.
// domeShadowFilter=taps (occluders.y 0): nine taps (a 3 × 3 grid spanning
// ±R) of the transmittance, averaged; averaging transmittance rather than
// exponentiating the mean optical depth avoids Jensen's bias (exp of a mean
// is at least the mean of exp). mipmap (occluders.y 1): the paper's
// convolution optical depth map (convolvedOpacityAt). Within a texel of z0
// (R < 1) it is the ordinary lookup; light views in perspective (not SRBFs)
// too.
// Through the density volume, a cone as wide as the lobe instead
// (densityVolumeLobeTransmittance).
float srbfShadowTransmittance(int i, vec3 centre) {
#if HDHAIR_FEATURE_DENSITY_VOLUME
    if (densityVolumeLight(i)) return densityVolumeLobeTransmittance(i, centre) * meshTransmittance(i, centre, 1.0);
#endif
#if !HDHAIR_FEATURE_SRBF_SHADOW_TAPS && !HDHAIR_FEATURE_SRBF_SHADOW_MIPMAP
    return shadowTransmittance(i, centre);  // no lobe of the pass has a map
#else
    if (shadows.mode.x == HDHAIR_SHADOW_OFF || shadows.lightMap[i].x < 0.0 || shadows.lightMap[i].w > 0.5)
        return shadowTransmittance(i, centre);
    vec4 clip = shadows.lightViewProjection[i] * vec4(centre, 1.0);
    vec2 position = (clip.xy / clip.w * 0.5 + 0.5) * float(shadows.mode.w);
    ivec2 texel = ivec2(floor(position));
    if (any(lessThan(texel, ivec2(0))) || any(greaterThanEqual(texel, ivec2(shadows.mode.w)))) return 1.0;
    float z = shadowLinearDepth(i, centre) - shadows.lightMap[i].z;
    float z0 = texelFetch(shadowDepths, ivec3(texel, shadowSlot(i)), 0).r;
    float lambda = lights.lightScale[i].w;
    float cosSupport = clamp(1.0 - 6.907755 / lambda, 1e-3, 1.0);  // ln(1000) = 6.907755
    float tanSupport = sqrt(max(1.0 - cosSupport * cosSupport, 0.0)) / cosSupport;
    float radius = 0.5 * (z - z0) * tanSupport / shadows.lightMap[i].z;  // texels
    if (!(radius >= 1.0) || z0 >= HDHAIR_NO_HAIR) return shadowTransmittance(i, centre);
    radius = min(radius, 0.25 * float(shadows.mode.w));
#if HDHAIR_FEATURE_SRBF_SHADOW_MIPMAP
#if HDHAIR_FEATURE_SRBF_SHADOW_TAPS
    if (shadows.occluders.y != 0)
#endif
    {  // domeShadowFilter=mipmap
        return exp(-shadows.extinction.x * convolvedOpacityAt(i, position, texel, z, radius)) *
               meshTransmittance(i, centre, 1.0);
    }
#endif
#if HDHAIR_FEATURE_SRBF_SHADOW_TAPS
    float sum = 0.0;
    for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x)
            sum += shadowTransmittanceAt(i, ivec2(floor(position + vec2(x, y) * radius)), z);
    return sum / 9.0 * meshTransmittance(i, centre, 1.0);
#endif
#endif
}

