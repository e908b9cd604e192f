#include "hdHair/render/ShadowPassUniforms.h"

#include "hdHair/plan/DeepOpacityLayers.h"

namespace hdhair {

namespace {

int modeOf(ShadowMode mode) {
    switch (mode) {
    // The plan's map mode is deepOpacity under auto and volume (ShadowPlan::mode).
    case ShadowMode::Auto:
    case ShadowMode::Volume:
    case ShadowMode::DeepOpacity: return gl::kShadowModeDeepOpacity;
    case ShadowMode::Reference: return gl::kShadowModeReference;
    case ShadowMode::Off: break;
    }
    return gl::kShadowModeOff;
}

// Everything but the lights.
gl::ShadowUniforms common(const ShadowPlan& shadows) {
    gl::ShadowUniforms uniforms;
    for (size_t i = 0; i < shadows.boundaries.size() && i < 4 * gl::kMaxShadowLayerVectors; ++i)
        uniforms.layerBoundaries[i / 4][int(i % 4)] = shadows.boundaries[i];
    uniforms.mode = glm::ivec4(modeOf(shadows.mode), shadows.layers, shadows.bilinear ? 1 : 0, shadows.resolution);
    uniforms.extinction = glm::vec4(kShadowExtinction, 0.0f, 0.0f, 0.0f);
    uniforms.occluders = glm::ivec4(shadows.meshesCast ? 1 : 0, shadows.convolvedOpacity ? 1 : 0,
                                    shadows.volumeBackScattering && shadows.usesVolume() ? 1 : 0,
                                    shadows.volumeDomeOcclusion && shadows.usesVolume() ? 1 : 0);
    if (shadows.usesVolume()) {
        const DensityGridShape& grid = shadows.volumeGrid;
        uniforms.volumeOrigin = glm::vec4(glm::vec3(grid.origin), float(grid.voxelSize));
        uniforms.volume = glm::ivec4(0, grid.dims);
    }
    for (glm::vec4& map : uniforms.lightMap) map.x = -1.0f;
    for (glm::vec4& map : uniforms.meshMap) map.x = -1.0f;
    return uniforms;
}

// Entry `entry` describes planned shadow `shadow`; no slot, no shadow.
// `borrowed`: the entry's light reads another light's map (an SRBF lobe,
// ShadowPlan::sharedMaps).
void setEntry(gl::ShadowUniforms& uniforms, int entry, const ShadowPlan& shadows, const PlannedShadow& shadow,
              bool borrowed = false) {
    const ShadowLightView& view = shadow.view;
    uniforms.lightViewProjection[entry] = glm::mat4(view.projection * view.view);
    uniforms.lightEye[entry] = glm::vec4(glm::vec3(view.eye), 0.0f);
    uniforms.lightForward[entry] = glm::vec4(glm::vec3(view.forward), 0.0f);
    if (shadow.byVolume && shadows.usesVolume()) uniforms.volume.x |= 1 << entry;
    const bool mapped = shadows.isMapped(shadow);
    uniforms.lightMap[entry] = glm::vec4(mapped ? float(shadow.slot) : -1.0f,
                                         float(shadows.layerDepth * (view.farDepth - view.nearDepth)),
                                         float(view.texelSize), view.orthographic ? 0.0f : 1.0f);
    if (!shadows.isMeshMapped(shadow)) return;
    const ShadowLightView& meshView = shadow.meshView;
    uniforms.meshViewProjection[entry] = glm::mat4(meshView.projection * meshView.view);
    uniforms.meshEye[entry] = glm::vec4(glm::vec3(meshView.eye), 0.0f);
    uniforms.meshForward[entry] = glm::vec4(glm::vec3(meshView.forward), 0.0f);
    uniforms.meshMap[entry] = glm::vec4(float(shadow.slot), float(meshView.texelSize),
                                        meshView.orthographic ? 0.0f : 1.0f, borrowed ? 0.0f : 1.0f);
}

}  // namespace

gl::ShadowUniforms batchShadowUniforms(const FrameRecipe& recipe, size_t batch) {
    gl::ShadowUniforms uniforms = common(recipe.shadows);
    auto [begin, end] = recipe.lighting.batches[batch];
    for (size_t light = begin; light < end && light - begin < size_t(gl::kMaxLightsPerPass); ++light) {
        const int shadow = recipe.shadows.shadowOf(light);
        if (shadow < 0) continue;
        const PlannedShadow& planned = recipe.shadows.lights[size_t(shadow)];
        setEntry(uniforms, int(light - begin), recipe.shadows, planned, planned.light != light);
    }
    return uniforms;
}

gl::ShadowUniforms lightShadowUniforms(const FrameRecipe& recipe, size_t shadow) {
    gl::ShadowUniforms uniforms = common(recipe.shadows);
    setEntry(uniforms, 0, recipe.shadows, recipe.shadows.lights[shadow]);
    return uniforms;
}

gl::FrameUniforms meshViewFrameUniforms(const FrameRecipe& recipe, size_t shadow, const gl::FrameUniforms& camera) {
    const ShadowLightView& view = recipe.shadows.lights[shadow].meshView;
    gl::FrameUniforms frame = lightViewFrameUniforms(recipe, shadow, camera);
    frame.viewProjection = glm::mat4(view.projection * view.view);
    frame.cameraPosition = glm::vec4(glm::vec3(view.eye), view.orthographic ? 0.0f : 1.0f);
    frame.cameraForward = glm::vec4(glm::vec3(view.forward), 0.0f);
    frame.pixelsPerUnit = float(view.pixelsPerUnit);
    return frame;
}

gl::FrameUniforms lightViewFrameUniforms(const FrameRecipe& recipe, size_t shadow, const gl::FrameUniforms& camera) {
    const ShadowLightView& view = recipe.shadows.lights[shadow].view;
    gl::FrameUniforms frame = camera;
    frame.viewProjection = glm::mat4(view.projection * view.view);
    frame.cameraPosition = glm::vec4(glm::vec3(view.eye), view.orthographic ? 0.0f : 1.0f);
    frame.cameraForward = glm::vec4(glm::vec3(view.forward), 0.0f);
    frame.viewportSize = glm::vec2(float(view.resolution));
    frame.pixelsPerUnit = float(view.pixelsPerUnit);
    frame.minPixelWidth = float(recipe.shadows.minPixelWidth);
    frame.drawMode = 1;
    frame.orderedDraw = 0;
    // The levels follow the light's texels, not the camera's pixels
    // (strand.tesc reads viewProjection and viewportSize), to a tolerance of
    // their own (shadowTessellationTolerance, half a texel by default): a map
    // holds each curve within it, in depth too, inside the one-texel bias
    // every lookup takes (shadows.glsl), so the camera's points on the same
    // curve do not shadow their own strand, and a deep opacity lookup, whose
    // opacity is continuous in depth behind the nearest hair, moves by a
    // fraction of a texel's worth. The camera's tolerance bounds what the
    // eye sees, a fraction of a pixel; a map a few hundred texels across
    // needs fewer segments than that, and does not change when only the
    // camera moves. The light views read no shadows: their spans are not cut
    // for vertex shadows either.
    if (frame.tessellationTolerance > 0.0f) frame.tessellationTolerance = float(recipe.shadows.tessellationTolerance);
    frame.shadowSegmentLength = 0.0f;
    return frame;
}

}  // namespace hdhair
