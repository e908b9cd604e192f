#pragma once
// Pre-multiplied "over" onto a constant background: hosts clear the colour
// AOV to their background (usdview) or to transparent black (usdrecord), and
// hdHair's empty pixels must show it as Storm's do.

#include <glm/vec4.hpp>

#include "hdHair/image/Image.h"

namespace hdhair::hydra {

// image (RGBA, pre-multiplied) = image + (1 - image.alpha) * background.
void compositeOver(Image& image, const glm::vec4& background);

}  // namespace hdhair::hydra
