#pragma once
// Hydra's camera, as the render pass state hands it over, in the engine's
// terms. No pxr here, so it is unit-tested without OpenUSD.
//
// GfMatrix4d multiplies row vectors (p' = p M) and stores rows in memory;
// read as a column-major glm matrix the same 16 doubles are the transpose,
// which is the same transform for column vectors (p' = M p). So the memory is
// taken as it is. The projection already includes the window policy and the
// framing (HdRenderPassState::GetProjectionMatrix), for an image the size of
// the data window.

#include "hdHair/plan/CameraView.h"
#include "hdHair/plan/RenderSettings.h"

namespace hdhair::hydra {

glm::dmat4 matrixFromGf(const double* gfMatrixData);

// Throws std::invalid_argument for a non-finite or singular matrix, or an
// empty image.
CameraView cameraViewFromHydra(const double* worldToView, const double* projection, int width, int height);

// Storm's refine level (usdrecord --complexity low/medium/high/veryhigh gives
// 0/1/2/3; 1.0-2.0 complexity maps to 0-8) as hdHair's complexity level.
Complexity complexityFromRefineLevel(int refineLevel);

}  // namespace hdhair::hydra
