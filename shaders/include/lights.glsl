// Lights in the form hdHair/shading/ShadingLight.h prepares them. Needs
// shadingFeatures.glsl.
#define HDHAIR_MAX_LIGHTS 16

layout(std140, binding = 1) uniform LightUniforms {
    // w = 0: xyz is the unit direction towards a distant light;
    // w = 1: xyz is the position of a local light;
    // w = 2: an SRBF light of a dome (srbfLighting.glsl): xyz its centre ξ.
    vec4 lightVector[HDHAIR_MAX_LIGHTS];
    // rgb: irradiance (distant) or irradiance times squared distance (local),
    // or an SRBF's amplitude L_j (radiance), its bandwidth λ in w.
    vec4 lightScale[HDHAIR_MAX_LIGHTS];
    // xyz: emission axis of one-sided emitters (rect, disk); w = 1 when one-sided.
    vec4 lightAxis[HDHAIR_MAX_LIGHTS];
    ivec4 lightCount;   // x: lights in use; y: the light batch (0 for the first)
    // rgb: dome light radiance; w = 0: a flat ambient term (radiance x colour),
    // w = 1: a uniform dome, shaded by its exact response (srbfLighting.glsl).
    vec4 ambient;
    // UsdLuxShapingAPI cone about lightAxis[i].xyz (ShadingLight::coneCosOuter,
    // coneCosInner, shaped): x = cos(cone angle), y = cos(angle * (1 - softness)),
    // z = 1 when the light is shaped, w unused.
    vec4 lightCone[HDHAIR_MAX_LIGHTS];
} lights;

// The cone's attenuation for a direction at cosine cosAngle to the light's
// axis; the same formula as coneFalloff() in hdHair/shading/ShadingLight.cpp.
float lightCone(int i, float cosAngle) {
    vec4 cone = lights.lightCone[i];
    if (cone.z < 0.5) return 1.0;
    if (cone.y <= cone.x) return cosAngle >= cone.x ? 1.0 : 0.0;
    return smoothstep(cone.x, cone.y, cosAngle);
}

bool isSrbfLight(int i) { return lights.lightVector[i].w > 1.5; }

// Irradiance from light i at a point, and the unit direction towards it. An
// SRBF light counts as the distant light it tends to as λ grows, of
// irradiance L_j ∫G dω = L_j 2π (1 − e^(−2λ))/λ (hdHair/environment/Srbf.h):
// what meshes (Lambert) use; hair reads the convolution tables instead.
vec3 lightIrradiance(int i, vec3 position, out vec3 toLight) {
    vec4 v = lights.lightVector[i];
#if HDHAIR_FEATURE_SRBF_LIGHTS
    if (v.w > 1.5) {
        toLight = v.xyz;
        float lambda = lights.lightScale[i].w;
        return lights.lightScale[i].rgb * (6.283185307179586 * (1.0 - exp(-2.0 * lambda)) / lambda);
    }
#endif
#if HDHAIR_FEATURE_LOCAL_LIGHTS
    if (v.w < 0.5) {
#endif
        toLight = v.xyz;
        return lights.lightScale[i].rgb;
#if HDHAIR_FEATURE_LOCAL_LIGHTS
    }
    vec3 offset = v.xyz - position;
    float distanceSquared = max(dot(offset, offset), 1e-12);
    toLight = offset * inversesqrt(distanceSquared);
    float cosAngle = dot(-toLight, lights.lightAxis[i].xyz);
    float facing = 1.0;
    if (lights.lightAxis[i].w > 0.5) facing = max(0.0, cosAngle);
    return lights.lightScale[i].rgb * (facing * lightCone(i, cosAngle) / distanceSquared);
#endif
}
