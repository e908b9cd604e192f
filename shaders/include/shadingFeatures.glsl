// Which parts of the shading a program compiles. As this file stands it
// compiles every part: it is what glslangValidator checks, and what every
// program but the strand passes' uses. The strand passes replace it, per
// program, with the parts their frame uses (hdHair/gl/ShadingFeatures.h
// writes the replacement from the uniforms and materials the draw reads):
// a software rasteriser such as llvmpipe runs a fragment's shader as masked
// SIMD, paying for every branch whether a fragment takes it or not, so code
// a frame cannot reach is cut out here rather than branched around. Each
// switch removes code only where its runtime condition is always false, so
// a program with a switch on draws exactly what one without it draws
// (testShaderSpecialization). The replacement may also define
// HDHAIR_SHADOW_LAYERS, the deep opacity maps' layer count, as a constant
// (shadows.glsl); this file leaves it to the uniform.
#ifndef HDHAIR_SHADING_FEATURES
#define HDHAIR_SHADING_FEATURES 1
#define HDHAIR_FEATURE_SHADE 1                // 0: the ids pass (drawMode 2) shades nothing
#define HDHAIR_FEATURE_KAJIYA_KAY 1           // a material of model 1
#define HDHAIR_FEATURE_MARSCHNER_TABLED 1     // a model 2 material without HAIR_MATERIAL_ANALYTIC
#define HDHAIR_FEATURE_MARSCHNER_ANALYTIC 1   // a model 2 material with it
#define HDHAIR_FEATURE_PER_POINT_PARAMETERS 1 // a material with HAIR_MATERIAL_PER_POINT
#define HDHAIR_FEATURE_SRBF_ABSORPTION 1      // a Marschner material with HAIR_MATERIAL_SRBF_LOBES
#define HDHAIR_FEATURE_DUAL_SCATTERING 1      // a Marschner material with HAIR_MATERIAL_DUAL_SCATTERING
#define HDHAIR_FEATURE_LOCAL_LIGHTS 1         // a light of kind 1 (lightVector.w)
#define HDHAIR_FEATURE_SRBF_LIGHTS 1          // a light of kind 2: a dome's SRBF lobe
#define HDHAIR_FEATURE_UNIFORM_DOME 1         // ambient.w 1: the uniform dome's exact response
#define HDHAIR_FEATURE_DEEP_OPACITY 1         // shadow mode deep opacity with a light that has a map
#define HDHAIR_FEATURE_SHADOW_REFERENCE 1     // shadow mode reference with a light that has a map
#define HDHAIR_FEATURE_BILINEAR_SHADOWS 1     // mode.z 1: shadowFilter=bilinear, a light having a map
#define HDHAIR_FEATURE_MESH_OCCLUDERS 1       // occluders.x: the meshes' depth in every slot
#define HDHAIR_FEATURE_SRBF_SHADOW_TAPS 1     // an SRBF lobe with a map, occluders.y 0
#define HDHAIR_FEATURE_SRBF_SHADOW_MIPMAP 1   // an SRBF lobe with a map, occluders.y 1
#define HDHAIR_FEATURE_DENSITY_VOLUME 1       // volume.x or occluders.w: a light or the uniform dome through the volume
#define HDHAIR_FEATURE_VOLUME_BACK_SCATTERING 1 // occluders.z: dual scattering's local term from the volume
#endif
