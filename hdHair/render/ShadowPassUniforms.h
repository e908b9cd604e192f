#pragma once
// What the GPU is told about shadows, from the plan: the shadow uniforms of
// a light batch (entry i for its i-th light) and of one light's shadow
// passes (entry 0), and the frame uniforms of a light's view.

#include "hdHair/gl/UniformBlocks.h"
#include "hdHair/plan/FrameRecipe.h"

namespace hdhair {

gl::ShadowUniforms batchShadowUniforms(const FrameRecipe& recipe, size_t batch);
gl::ShadowUniforms lightShadowUniforms(const FrameRecipe& recipe, size_t shadow);

// The camera's frame seen from a light: its settings kept, the light's
// projection, eye and pixels (which the tessellation levels follow: the
// tolerance is in the map's texels), ribbons facing the light, the coverage
// rule at recipe.shadows.minPixelWidth, unordered.
gl::FrameUniforms lightViewFrameUniforms(const FrameRecipe& recipe, size_t shadow, const gl::FrameUniforms& camera);
// The same from the view the light's mesh depth is drawn from
// (PlannedShadow::meshView).
gl::FrameUniforms meshViewFrameUniforms(const FrameRecipe& recipe, size_t shadow, const gl::FrameUniforms& camera);

}  // namespace hdhair
