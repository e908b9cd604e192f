#pragma once
// C++ mirrors of the std140 uniform blocks in shaders/include/. Field order
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
    int32_t shadingModel = 1;    // 0 flat, 1 Kajiya-Kay
    int32_t drawMode = 0;        // 0 opaque, 1 pre-multiplied, 2 depth and ids only
    int32_t orderedDraw = 0;     // 1: patches come through the draw-order buffer
    int32_t padding[3] = {0, 0, 0};
};
static_assert(sizeof(FrameUniforms) == 144, "std140 layout of FrameUniforms");

struct LightUniforms {  // binding 1, shaders/include/lights.glsl
    glm::vec4 lightVector[kMaxLightsPerPass]{};
    glm::vec4 lightScale[kMaxLightsPerPass]{};
    glm::vec4 lightAxis[kMaxLightsPerPass]{};
    glm::ivec4 lightCount{0};
    glm::vec4 ambient{0.0f};
    glm::vec4 kajiyaKayParameters{0.0f};
    // Spot shaping: x cos(cone angle), y cos(angle * (1 - softness)), z 1 when shaped.
    glm::vec4 lightCone[kMaxLightsPerPass]{};
};
static_assert(sizeof(LightUniforms) == 16 * 4 * kMaxLightsPerPass + 48, "std140 layout of LightUniforms");

}  // namespace hdhair::gl
