#pragma once
// C++ mirrors of the std140 uniform blocks (and std430 storage structs) in
// shaders/include/. Field order
// and padding must match the GLSL declarations exactly.

#include <cstdint>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

namespace hdhair::gl {

constexpr int kMaxLightsPerPass = 16;  // HDHAIR_MAX_LIGHTS in shaders/include/lights.glsl

struct FrameUniforms {  // binding 0, shaders/include/frameUniforms.glsl
    glm::mat4 viewProjection{1.0f};
    glm::vec4 cameraPosition{0.0f};
    glm::vec4 cameraForward{0.0f, 0.0f, -1.0f, 0.0f};
    glm::vec2 viewportSize{1.0f};
    float pixelsPerSegment = 8.0f;
    float maxSegmentsPerSpan = 8.0f;
    float pixelsPerUnit = 1.0f;  // pixels a world unit spans at clip w = 1
    float minPixelWidth = 0.0f;  // sub-pixel coverage threshold; 0 keeps true widths
    int32_t drawMode = 0;        // 0 opaque, 1 pre-multiplied, 2 ids only (the ids pass)
    int32_t orderedDraw = 0;     // 1: patches come through the draw-order buffer
    // Blended frames: the least alpha (coverage x opacity) of a fragment that
    // may give its pixel depth and ids (hdHair/plan/NearestStrandRule.h).
    float nearestStrandMinAlpha = 0.0f;
    // screenError tessellation: the most a centre line may stray from its
    // curve, in this pass's pixels (a light view's texels); 0 selects
    // projectedLength (pixelsPerSegment) instead.
    float tessellationTolerance = 0.0f;
    float padding0[2] = {0.0f, 0.0f};  // std140: the mat3 below starts on 16 bytes
    // From the rendering space back to linear Rec.709, as std140 mat3
    // columns: screenError tessellation measures colour in the space colours
    // are authored in, so the geometry does not depend on renderingSpace.
    glm::vec4 colorToRec709[3] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};
    // Vertex shadows (shadowSampling=vertex): the longest a segment may be,
    // world units, in the camera's passes, so that the transmittance
    // interpolated along it resolves the finest shadow map
    // (vertexShadowSegmentLength in hdHair/render/ShadowPassUniforms.h); 0:
    // no limit, and in the light views.
    float shadowSegmentLength = 0.0f;
    float padding[3] = {0.0f, 0.0f, 0.0f};
};
static_assert(sizeof(FrameUniforms) == 208, "std140 layout of FrameUniforms");

struct LightUniforms {  // binding 1, shaders/include/lights.glsl
    glm::vec4 lightVector[kMaxLightsPerPass]{};
    glm::vec4 lightScale[kMaxLightsPerPass]{};
    glm::vec4 lightAxis[kMaxLightsPerPass]{};
    glm::ivec4 lightCount{0};  // x: lights in use; y: the light batch (0 for the first)
    glm::vec4 ambient{0.0f};
    // Spot shaping: x cos(cone angle), y cos(angle * (1 - softness)), z 1 when shaped.
    glm::vec4 lightCone[kMaxLightsPerPass]{};
};
static_assert(sizeof(LightUniforms) == 16 * 4 * kMaxLightsPerPass + 32, "std140 layout of LightUniforms");

// How a pass's lights shadow the hair (binding 2, shaders/include/shadows.glsl;
// hdHair/plan/DeepOpacityLayers.h has the formulas). Light i of a pass is
// entry i; a shadow pass writes its one light as entry 0.
constexpr int kMaxShadowLayerVectors = 8;  // 32 layer boundaries, 4 a vec4
struct ShadowUniforms {
    glm::mat4 lightViewProjection[kMaxLightsPerPass]{};  // world to the light view's clip space
    glm::vec4 lightEye[kMaxLightsPerPass]{};             // xyz: the light view's eye
    glm::vec4 lightForward[kMaxLightsPerPass]{};         // xyz: its unit viewing direction
    // x: the map's slot (-1: the light casts no shadow), y: d_K, the last
    // layer's depth behind the nearest hair (world units), z: a texel's world
    // size (at linear depth 1 when perspective), w: 1 perspective, 0 orthographic.
    glm::vec4 lightMap[kMaxLightsPerPass]{};
    glm::vec4 layerBoundaries[kMaxShadowLayerVectors]{};  // d_k / d_K, k = 1..32
    // x: 0 off, 1 deep opacity maps, 2 reference; y: layers; z: filter
    // (0 nearest, 1 bilinear); w: the maps' resolution.
    glm::ivec4 mode{0};
    glm::vec4 extinction{1.0f, 0.0f, 0.0f, 0.0f};  // x: k of T = exp(-k opacity)
    // x: 1 when meshes cast shadows: every slot's mesh depth (the nearest
    // mesh in the light's view) is current and hides the strands behind it.
    // y: 1 when SRBF lights read the opacity layers' mip chain
    // (domeShadowFilter=mipmap, ShadowPlan::convolvedOpacity). z: 1 when
    // the hair behind each fibre, which dual scattering's local term sends
    // back, is read from the density volume (ShadowPlan::volumeBackScattering).
    // w: 1 when the uniform dome reaches the strands through the density
    // volume (ShadowPlan::volumeDomeOcclusion).
    glm::ivec4 occluders{0};
    // The view each light's mesh depth is drawn from (PlannedShadow::meshView):
    // world to its clip space, its eye (xyz) and unit viewing direction (xyz);
    // x: the slot of its mesh depth (-1: none), y: a texel's world size (at
    // linear depth 1 when perspective), z: 1 perspective, 0 orthographic,
    // w: 1 when the view is the light's own, 0 when borrowed (an SRBF lobe
    // reading another lobe's map: meshes do not shadow themselves through it).
    glm::mat4 meshViewProjection[kMaxLightsPerPass]{};
    glm::vec4 meshEye[kMaxLightsPerPass]{};
    glm::vec4 meshForward[kMaxLightsPerPass]{};
    glm::vec4 meshMap[kMaxLightsPerPass]{};
    // The hair density volume (hdHair/curves/HairDensityGrid.h): xyz its
    // lowest corner, w a voxel's edge; x: a bit per light of the pass
    // shadowed through it, yzw: its voxels along x, y, z.
    glm::vec4 volumeOrigin{0.0f};
    glm::ivec4 volume{0};
};
static_assert(sizeof(ShadowUniforms) == 64 * kMaxLightsPerPass + 48 * kMaxLightsPerPass + 16 * 8 + 48 +
                                            112 * kMaxLightsPerPass + 32,
              "std140 layout of ShadowUniforms");
constexpr int kShadowModeOff = 0, kShadowModeDeepOpacity = 1, kShadowModeReference = 2;

// One element of the HairMaterials storage buffer (shaders/include/hairMaterials.glsl).
struct GpuHairMaterial {
    // x: model (0 flat, 1 Kajiya-Kay, 2 Marschner); y: first table layer;
    // z: flags (kHairMaterial*); w: first per-point record.
    glm::ivec4 modelAndLayer{1, 0, 0, 0};
    // x: the prim's first segment (per-point materials); y, z: its SRBF table
    // and uniform-dome row; w: its dual-scattering layer (kHairMaterialDualScattering)
    glm::ivec4 segments{0};
    glm::vec4 kajiyaKay{0.0f};            // Kd, Ks, p
    glm::vec4 alphaEta{0.0f};             // Marschner alpha_R, alpha_TT, alpha_TRT; eta
    glm::vec4 betaGlint{0.0f};            // Marschner beta_R, beta_TT, beta_TRT; glint scale k_G
    glm::vec4 sigmaA{0.0f};               // Marschner sigma_a; caustic width w_c
    glm::vec4 caustic{0.0f};              // caustic fade, caustic limit; dual scattering's d_f, d_b
};
static_assert(sizeof(GpuHairMaterial) == 112, "std430 layout of HairMaterial");
constexpr int kHairMaterialPerPoint = 1;  // HAIR_MATERIAL_PER_POINT
constexpr int kHairMaterialAnalytic = 2;  // HAIR_MATERIAL_ANALYTIC
constexpr int kHairMaterialSrbfLobes = 4;  // HAIR_MATERIAL_SRBF_LOBES
constexpr int kHairMaterialDualScattering = 8;  // HAIR_MATERIAL_DUAL_SCATTERING

}  // namespace hdhair::gl
