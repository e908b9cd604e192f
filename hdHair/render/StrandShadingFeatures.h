#pragma once
// The parts of the strand shading (hdHair/gl/ShadingFeatures.h) a draw of
// one light batch reaches, read from the plan: the strand programs compile
// only those (specializeShaders). Nothing is decoded from the uniforms the
// draw binds; ShadowPassUniforms.h and the light uniforms are made from the
// same plan.

#include <cstddef>
#include <vector>

#include "hdHair/gl/ShadingFeatures.h"
#include "hdHair/plan/FrameRecipe.h"
#include "hdHair/plan/HairMaterial.h"

namespace hdhair {

// What a frame's hair materials call for, whichever prims read them: each
// lit model (Marschner tabled or analytic), multiple scattering, parameters
// per curve or vertex, and, when the frame has dome tables (`domeTables`), Marschner absorption
// per fragment under the dome (srbfAbsorbsPerFragment).
gl::ShadingFeatures materialShadingFeatures(const std::vector<HairMaterial>& materials, bool domeTables);

// Batch `batch`'s draw, its materials calling for `materials`: shading; the
// uniform dome's response (the first batch only, which alone carries it);
// local and SRBF lights; and for each light with a map (ShadowPlan::isMapped)
// its lookup: deep opacity with the plan's layer count compiled in, or the
// reference's fragment lists; the meshes' depth, the bilinear filter, and an
// SRBF light's widening (mip chain or taps) as planned.
gl::ShadingFeatures batchShadingFeatures(const FrameRecipe& recipe, size_t batch, const gl::ShadingFeatures& materials);

// How many of batch `batch`'s lights vertex shadows look up: up to the last
// that reads a deep opacity map (0: none; reference shadows are always
// looked up per fragment).
int batchVertexShadowLights(const FrameRecipe& recipe, size_t batch);

}  // namespace hdhair
