// Hair materials (hdHair/render/HairMaterial.h), one per distinct prim
// material in the frame; hdHair/gl/HairMaterialTable.h fills them.
struct HairMaterial {
    ivec4 modelAndLayer;  // x: 0 flat, 1 Kajiya-Kay, 2 Marschner; y: first layer of its Marschner tables
    vec4 kajiyaKay;       // x: Kd, y: Ks, z: shininess p
    vec4 alpha;           // Marschner alpha_R, alpha_TT, alpha_TRT (radians)
    vec4 beta;            // Marschner beta_R, beta_TT, beta_TRT (radians)
};
layout(std430, binding = 8) readonly buffer HairMaterials {
    HairMaterial materials[];
};
// Every Marschner material's azimuthal tables, two layers each
// (hdHair/shading/MarschnerTables.h).
layout(binding = 1) uniform sampler2DArray marschnerTables;
