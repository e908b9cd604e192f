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
    // may give its pixel depth and ids (hdHair/render/NearestStrandRule.h).
    float nearestStrandMinAlpha = 0.0f;
    float padding_[3]{};  // std140 rounds the block up to whole vec4s
};
static_assert(sizeof(FrameUniforms) == 144, "std140 layout of FrameUniforms");

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

// One element of the HairMaterials storage buffer (shaders/include/hairMaterials.glsl).
struct GpuHairMaterial {
    // x: model (0 flat, 1 Kajiya-Kay, 2 Marschner); y: first table layer;
    // z: flags (kHairMaterialPerPoint, kHairMaterialAnalytic); w: first per-point record.
    glm::ivec4 modelAndLayer{1, 0, 0, 0};
    glm::ivec4 segments{0};               // x: the prim's first segment (per-point materials)
    glm::vec4 kajiyaKay{0.0f};            // Kd, Ks, p
    glm::vec4 alphaEta{0.0f};             // Marschner alpha_R, alpha_TT, alpha_TRT; eta
    glm::vec4 betaGlint{0.0f};            // Marschner beta_R, beta_TT, beta_TRT; glint scale k_G
    glm::vec4 sigmaA{0.0f};               // Marschner sigma_a; caustic width w_c
    glm::vec4 caustic{0.0f};              // caustic fade, caustic limit
};
static_assert(sizeof(GpuHairMaterial) == 112, "std430 layout of HairMaterial");
constexpr int kHairMaterialPerPoint = 1;  // HAIR_MATERIAL_PER_POINT
constexpr int kHairMaterialAnalytic = 2;  // HAIR_MATERIAL_ANALYTIC

}  // namespace hdhair::gl
