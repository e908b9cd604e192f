#pragma once
// Averages each factor x factor block of an image into one pixel: a
// supersampled render brought to its output size, every sample weighted
// alike (pre-multiplied colours average correctly; coverage becomes alpha).

#include "hdHair/image/Image.h"

namespace hdhair {

// `image`'s width and height must be multiples of `factor` (>= 1); throws
// std::invalid_argument otherwise.
Image boxDownsample(const Image& image, int factor);

}  // namespace hdhair
