// A dome's light on a strand (hdHair/plan/DomeLighting.h): SRBF lights,
// each read from its material's SRBF-convolution table, and a uniform dome's
// exact response. Ren, Zhou, Li, Hua & Guo 2010, eq. (4): lobe j adds
//   L_j T̃_j I(ωo; ξ_j, λ_j),  I = ∫ G(ωi; ξ_j, λ_j) f(ωi, ωo) dωi,
// I from the table (hdHair/shading/SrbfConvolutionTables.h has the layout
// and the lookup this mirrors, sampleSrbfTable on the CPU): Marschner RGB,
// or Kajiya-Kay (diffuse, specular) for Kd = Ks = 1, scaled here by
// Kd·colour and Ks. T̃_j, the shadow, is the caller's.
// hdHair/gl/SrbfTableTextures.h says how tables of several materials share
// one texture: side by side along x, table k at x = k·width.
// Needs lights.glsl, hairMaterials.glsl and marschnerAnalytic.glsl, after
// shadingFeatures.glsl (a flat-only frame calls none of this).

layout(binding = 5) uniform sampler3D srbfMarschnerTables;  // RGB, 32 ψ × 64 θ_o × 512 a table
layout(binding = 6) uniform sampler3D srbfKajiyaKayTables;  // RG, 1 × 64 × 512 a table
layout(binding = 7) uniform sampler2D srbfUniformDome;      // a row of 64 θ_o nodes a table

const int SRBF_TABLE_AZIMUTHS = 32;   // ψ nodes of a Marschner table (Kajiya-Kay: 1)
const int SRBF_TABLE_CENTRES = 64;    // θ_ξ nodes a slab
const int SRBF_TABLE_BANDWIDTHS = 8;  // slabs, 1/λ from 1/64 to 1/16
const float SRBF_PI = 3.14159265358979;

// Node coordinate u in [0, count - 1] of `value` on [low, high] (both ends nodes).
float srbfNode(float value, float low, float high, int count) {
    return clamp((value - low) / (high - low) * float(count - 1), 0.0, float(count - 1));
}

// The table's angles (srbfTableAngles on the CPU): θ_o and θ_ξ signed from
// the normal plane, ψ between the projections on it (0 when either is 0).
vec3 srbfTableAngles(vec3 t, vec3 e, vec3 xi) {
    float sinO = clamp(dot(t, e), -1.0, 1.0), sinXi = clamp(dot(t, xi), -1.0, 1.0);
    vec3 po = e - sinO * t, pXi = xi - sinXi * t;
    float lengths = length(po) * length(pXi);
    float psi = lengths > 1e-12 ? atan(length(cross(pXi, po)), dot(pXi, po)) : 0.0;
    return vec3(asin(sinO), asin(sinXi), psi);
}

// Table `table` (of `width` ψ nodes) of `tables` at angles (θ_o, θ_ξ, ψ) and
// bandwidth λ: trilinear in (ψ, θ_o, θ_ξ) within the two nearest 1/λ slabs,
// mixed linearly in 1/λ.
vec3 sampleSrbfTable(sampler3D tables, int table, int width, vec3 angles, float lambda) {
    ivec3 size = textureSize(tables, 0);
    float uPsi = srbfNode(angles.z, 0.0, SRBF_PI, width);
    float uO = srbfNode(angles.x, -0.5 * SRBF_PI, 0.5 * SRBF_PI, size.y);
    float uXi = srbfNode(angles.y, -0.5 * SRBF_PI, 0.5 * SRBF_PI, SRBF_TABLE_CENTRES);
    float uLambda = srbfNode(1.0 / lambda, 1.0 / 64.0, 1.0 / 16.0, SRBF_TABLE_BANDWIDTHS);
    int l0 = min(int(floor(uLambda)), SRBF_TABLE_BANDWIDTHS - 1);
    int l1 = min(l0 + 1, SRBF_TABLE_BANDWIDTHS - 1);
    float s = (float(table * width) + uPsi + 0.5) / float(size.x);
    float tt = (uO + 0.5) / float(size.y);
    vec3 a = texture(tables, vec3(s, tt, (float(l0 * SRBF_TABLE_CENTRES) + uXi + 0.5) / float(size.z))).rgb;
    vec3 b = texture(tables, vec3(s, tt, (float(l1 * SRBF_TABLE_CENTRES) + uXi + 0.5) / float(size.z))).rgb;
    return mix(a, b, uLambda - float(l0));
}

// Marschner prims whose absorption varies per curve or vertex
// (HAIR_MATERIAL_SRBF_LOBES) read a table of the lobes apart at σ_a = 0,
// (R, TT, TRT), and put the fragment's absorption back as each lobe's energy
// ratio T̄_p = ∫A(p, h; σ_a) dh / ∫A(p, h; 0) dh at its θ_o, a 16-node
// midpoint rule in h, once per fragment for every lobe
// (hdHair/shading/SrbfVaryingAbsorption.h, which measures its error).
struct SrbfAbsorption {
    bool perFragment;
    vec3 tt, trt;  // T̄_TT, T̄_TRT
};

vec3 srbfEnergyRatio(vec3 absorbed, vec3 white) {
    vec3 ratio;
    for (int c = 0; c < 3; ++c) ratio[c] = white[c] > 0.0 ? clamp(absorbed[c] / white[c], 0.0, 1.0) : 1.0;
    return ratio;
}

// No fragment's absorption: what srbfAbsorption gives every material
// without HAIR_MATERIAL_SRBF_LOBES.
SrbfAbsorption srbfNoAbsorption() {
    SrbfAbsorption absorption;
    absorption.perFragment = false;
    absorption.tt = absorption.trt = vec3(1.0);
    return absorption;
}

SrbfAbsorption srbfAbsorption(HairShading shading, vec3 t, vec3 e) {
    SrbfAbsorption absorption;
    absorption.perFragment = shading.model == 2 && (shading.flags & HAIR_MATERIAL_SRBF_LOBES) != 0;
    absorption.tt = absorption.trt = vec3(1.0);
    if (!absorption.perFragment) return absorption;
    float sinO = clamp(dot(t, e), -1.0, 1.0);
    float cosO = sqrt(max(0.0, 1.0 - sinO * sinO));
    MarschnerFibre clear = shading.fibre;
    clear.sigmaA = vec3(0.0);
    MarschnerAzimuthalSetup absorbing = marschnerAzimuthalSetup(cosO, shading.fibre);
    MarschnerAzimuthalSetup white = marschnerAzimuthalSetup(cosO, clear);
    vec3 tt = vec3(0.0), ttWhite = vec3(0.0), trt = vec3(0.0), trtWhite = vec3(0.0);
    for (int i = 0; i < 16; ++i) {
        float h = (float(i) + 0.5) / 16.0;
        tt += marschnerAttenuation(1, h, absorbing);
        ttWhite += marschnerAttenuation(1, h, white);
        trt += marschnerAttenuation(2, h, absorbing);
        trtWhite += marschnerAttenuation(2, h, white);
    }
    absorption.tt = srbfEnergyRatio(tt, ttWhite);
    absorption.trt = srbfEnergyRatio(trt, trtWhite);
    return absorption;
}

// A Marschner table's value as RGB radiance: as it is, or R + T̄_TT·TT + T̄_TRT·TRT.
vec3 srbfMarschnerRadiance(vec3 tableValue, SrbfAbsorption absorption) {
    if (!absorption.perFragment) return tableValue;
    return vec3(tableValue.x) + absorption.tt * tableValue.y + absorption.trt * tableValue.z;
}

// The radiance SRBF light i scatters towards the eye per unit transmittance:
// L_j · I for Marschner, L_j · (Kd·colour·I_d + Ks·I_s) for Kajiya-Kay.
// materials[m].segments.y is the material's table among its kind's.
vec3 srbfLightRadiance(int i, int materialIndex, HairShading shading, SrbfAbsorption absorption, vec3 t, vec3 e,
                       vec3 hairColor) {
    vec3 angles = srbfTableAngles(t, e, lights.lightVector[i].xyz);
    float lambda = lights.lightScale[i].w;
    int table = materials[materialIndex].segments.y;
#if HDHAIR_FEATURE_MARSCHNER_TABLED || HDHAIR_FEATURE_MARSCHNER_ANALYTIC
#if HDHAIR_FEATURE_KAJIYA_KAY
    if (shading.model == 2)
#endif
        return lights.lightScale[i].rgb *
               srbfMarschnerRadiance(sampleSrbfTable(srbfMarschnerTables, table, SRBF_TABLE_AZIMUTHS, angles, lambda),
                                     absorption);
#endif
#if HDHAIR_FEATURE_KAJIYA_KAY
    vec2 terms = sampleSrbfTable(srbfKajiyaKayTables, table, 1, angles, lambda).xy;
    return lights.lightScale[i].rgb * (shading.kajiyaKay.x * terms.x * hairColor + shading.kajiyaKay.y * terms.y);
#else
    return vec3(0.0);  // not reached: the frame has no Kajiya-Kay material
#endif
}

// The radiance a uniform dome of radiance 1 sends towards the eye
// (hdHair/shading/SrbfUniformDome.h: ∫ f dωi, per θ_o node, row
// materials[m].segments.z), interpolated linearly in θ_o.
vec3 srbfUniformDomeResponse(int materialIndex, HairShading shading, SrbfAbsorption absorption, vec3 t, vec3 e,
                             vec3 hairColor) {
    ivec2 size = textureSize(srbfUniformDome, 0);
    int row = materials[materialIndex].segments.z;
    float u = srbfNode(asin(clamp(dot(t, e), -1.0, 1.0)), -0.5 * SRBF_PI, 0.5 * SRBF_PI, size.x);
    int x0 = min(int(floor(u)), size.x - 1), x1 = min(x0 + 1, size.x - 1);
    vec3 response = mix(texelFetch(srbfUniformDome, ivec2(x0, row), 0).rgb,
                        texelFetch(srbfUniformDome, ivec2(x1, row), 0).rgb, u - float(x0));
#if HDHAIR_FEATURE_MARSCHNER_TABLED || HDHAIR_FEATURE_MARSCHNER_ANALYTIC
#if HDHAIR_FEATURE_KAJIYA_KAY
    if (shading.model == 2)
#endif
        return srbfMarschnerRadiance(response, absorption);
#endif
#if HDHAIR_FEATURE_KAJIYA_KAY
    return shading.kajiyaKay.x * response.x * hairColor + shading.kajiyaKay.y * response.y;
#else
    return vec3(0.0);  // not reached: the frame has no Kajiya-Kay material
#endif
}
