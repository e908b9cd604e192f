#pragma once
// Pixel comparison for image tests, in the spirit of OpenImageIO's idiff
// (which OpenUSD's image tests use): a per-channel absolute difference, a
// failure threshold, and the fraction of pixels allowed to exceed it.

#include <string>

#include "hdHair/image/Image.h"

namespace hdhair {

struct ImageDifference {
    bool sizesMatch = false;
    double maxDifference = 0.0;       // largest per-channel absolute difference
    double meanDifference = 0.0;      // over all channels
    double rootMeanSquare = 0.0;
    double fractionOverThreshold = 0.0;  // pixels with any channel over `threshold`
};

ImageDifference compareImages(const Image& actual, const Image& expected, double threshold);

// A baseline test's verdict with its stated thresholds: at most
// `allowedFraction` of pixels may differ by more than `threshold` in any
// channel, and no channel anywhere by more than `hardLimit`.
struct ImageTolerance {
    double threshold = 2.0 / 255.0;
    double allowedFraction = 0.002;
    double hardLimit = 0.25;
};

bool withinTolerance(const ImageDifference& difference, const ImageTolerance& tolerance);
std::string describe(const ImageDifference& difference, const ImageTolerance& tolerance);

}  // namespace hdhair
