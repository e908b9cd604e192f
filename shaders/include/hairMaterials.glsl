// Hair materials (hdHair/plan/HairMaterial.h), one per distinct prim
// material in the frame, and the per-control-point hair parameters of prims
// whose parameters vary per curve or per vertex; hdHair/gl/HairMaterialTable.h
// fills both. Needs catmullRom.glsl, marschnerAnalytic.glsl and strandGeometry.glsl,
// after shadingFeatures.glsl.
struct HairMaterial {
    ivec4 modelAndLayer;  // x: 0 flat, 1 Kajiya-Kay, 2 Marschner; y: first layer of its Marschner tables;
                          // z: flags (HAIR_MATERIAL_*); w: its prim's first per-point record
    ivec4 segments;       // x: its prim's first control point (per-point materials only); y, z: its SRBF
                          // table and uniform-dome row (srbfLighting.glsl); w: its dual-scattering layer
    vec4 kajiyaKay;       // x: Kd, y: Ks, z: shininess p
    vec4 alphaEta;        // Marschner alpha_R, alpha_TT, alpha_TRT (radians); w: eta
    vec4 betaGlint;       // Marschner beta_R, beta_TT, beta_TRT (radians); w: glint scale k_G
    vec4 sigmaA;          // Marschner sigma_a (per fibre radius); w: caustic width w_c
    vec4 caustic;         // x: caustic fade delta eta', y: caustic limit delta h_M;
                          // z, w: dual scattering's densities d_f, d_b (dualScattering.glsl)
};
const int HAIR_MATERIAL_PER_POINT = 1;  // parameters come from the per-point records
const int HAIR_MATERIAL_ANALYTIC = 2;   // Marschner's azimuthal terms per fragment, not from tables
const int HAIR_MATERIAL_SRBF_LOBES = 4; // dome lighting: absorption per fragment (srbfLighting.glsl)
const int HAIR_MATERIAL_DUAL_SCATTERING = 8; // multiple scattering (dualScattering.glsl)

layout(std430, binding = 8) readonly buffer HairMaterials {
    HairMaterial materials[];
};
// Two vec4s a control point, parallel to the prim's control points (shared
// between spans as they are), for the prims whose material has
// HAIR_MATERIAL_PER_POINT, in the model's meaning:
//   Kajiya-Kay: (Kd, Ks, p, 0), unused;
//   Marschner:  (sigma_a, eta), (alpha_R, beta_R, 0, 0) in radians.
layout(std430, binding = 9) readonly buffer HairParameterPoints {
    vec4 hairParameterPoints[];
};
// Every tabled Marschner material's azimuthal tables, two layers each
// (hdHair/shading/MarschnerTables.h), and every dual-scattering material's
// fibre layer (hdHair/shading/DualScattering.h).
layout(binding = 1) uniform sampler2DArray marschnerTables;

// A fragment's hair parameters: its material's, or its prim's per-point values
// interpolated with the Catmull-Rom weights the positions use (clamped, as
// cubic interpolation can overshoot).
struct HairShading {
    int model;
    int flags;
    float tableLayer;
    float dualLayer;      // its dual-scattering layer (HAIR_MATERIAL_DUAL_SCATTERING)
    vec2 dualDensities;   // d_f, d_b
    vec3 kajiyaKay;
    MarschnerFibre fibre;
};

HairShading hairShadingAt(int materialIndex, int segment, float u) {
    HairMaterial material = materials[materialIndex];
    HairShading shading;
    shading.model = material.modelAndLayer.x;
    shading.flags = material.modelAndLayer.z;
    shading.tableLayer = float(material.modelAndLayer.y);
    shading.dualLayer = float(material.segments.w);
    shading.dualDensities = material.caustic.zw;
    shading.kajiyaKay = material.kajiyaKay.xyz;
    shading.fibre.sigmaA = material.sigmaA.xyz;
    shading.fibre.eta = material.alphaEta.w;
    shading.fibre.alpha = material.alphaEta.xyz;
    shading.fibre.beta = material.betaGlint.xyz;
    shading.fibre.glintScale = material.betaGlint.w;
    shading.fibre.causticWidth = material.sigmaA.w;
    shading.fibre.causticFade = material.caustic.x;
    shading.fibre.causticLimit = material.caustic.y;
#if HDHAIR_FEATURE_PER_POINT_PARAMETERS
    if ((shading.flags & HAIR_MATERIAL_PER_POINT) == 0) return shading;

    vec4 w = catmullRomWeights(clamp(u, 0.0, 1.0));
    int first = 2 * (material.modelAndLayer.w + int(segmentFirstControl[segment]) - material.segments.x);
    vec4 a = vec4(0.0), b = vec4(0.0);
    for (int k = 0; k < 4; ++k) {
        a += w[k] * hairParameterPoints[first + 2 * k];
        b += w[k] * hairParameterPoints[first + 2 * k + 1];
    }
    if (shading.model == 1) {
        shading.kajiyaKay = vec3(max(a.xy, vec2(0.0)), max(a.z, 1.0));
    } else if (shading.model == 2) {
        shading.fibre.sigmaA = max(a.xyz, vec3(0.0));
        shading.fibre.eta = max(a.w, 1.0);
        // Marschner 2003 Table 1: the TT and TRT lobes follow R.
        shading.fibre.alpha = b.x * vec3(1.0, -0.5, -1.5);
        shading.fibre.beta = b.y * vec3(1.0, 0.5, 2.0);
    }
#endif
    return shading;
}
