#pragma once
// The one rule every image test compares by: statistics over the pixels
// something covers, not the whole frame, so that a frame mostly of empty
// background cannot dilute a changed shade into a pass.
//
// A pixel is covered when its alpha (the last of four channels) is above
// 1/255 in either image; images without alpha count every pixel. A covered
// pixel whose largest channel difference is over the outlier limit is an
// outlier: a strand edge that landed a pixel away (another CPU rounds it the
// other way). One whose largest difference is over the threshold but within
// the outlier limit is shaded differently. The images agree when the pixels
// shaded differently stay within the allowed share of covered pixels and the
// outliers within the allowed count: a changed shade moves many pixels a
// little and fails; a handful of edges a pixel apart passes.
//
// Colour values are compared as stored: linear pre-multiplied floats from an
// EXR or a render, 8-bit sRGB with straight alpha from a PNG. A NaN or an
// infinity anywhere is an outlier.

#include <cstddef>
#include <string>

#include "hdHair/image/Image.h"

namespace hdhair {

struct CoveredPixelTolerance {
    double threshold = 0.0;                  // per-channel difference any covered pixel may have
    double allowedShareOverThreshold = 0.0;  // of covered pixels (0..1) over the threshold, within the outlier limit
    double outlierLimit = 0.0;               // per-channel difference that makes an outlier
    size_t allowedOutliers = 0;
};

// A tolerance that allows no difference above `limit` anywhere covered (every
// pixel over it is an outlier, and none is allowed).
CoveredPixelTolerance exactWithin(double limit);

struct ImageComparison {
    bool sizesMatch = false;
    size_t coveredPixels = 0;
    size_t pixelsOverThreshold = 0;   // over the threshold, within the outlier limit
    size_t outliers = 0;              // over the outlier limit
    double shareOverThreshold = 0.0;  // pixelsOverThreshold / coveredPixels (0 when none is covered)
    // Over covered pixels, every channel:
    double maxDifference = 0.0;
    double meanDifference = 0.0;
    double rootMeanSquare = 0.0;
    // The covered pixel and channel with the largest difference (-1 when none differs).
    int worstX = -1, worstY = -1, worstChannel = -1;
    float worstActual = 0.0f, worstExpected = 0.0f;
    bool passed = false;
    // One line: the verdict, the counts against their allowances, and the
    // worst pixel with both values.
    std::string description;
};

ImageComparison compareImages(const Image& actual, const Image& expected, const CoveredPixelTolerance& tolerance);

// An image's colour error relative to a reference, over the pixels either
// covers and the colour channels only (RGB of RGBA; alpha, the same
// coverage in both, would dilute it): the RMS of the difference over the RMS
// of the reference (the SRBF fit's relative L2 measure, on pixels), and the
// largest difference over the reference's largest value; and the ratio of
// their sums (the bias: 1.1 is 10 % too bright overall). What the dome
// lighting's bounds against its reference are stated in (testDomeReference,
// hdhair-bench --table dome). Both 0 when nothing is covered; sizes must match
// (std::invalid_argument otherwise).
struct RelativeColorError {
    size_t coveredPixels = 0;
    double rootMeanSquare = 0.0;
    double largest = 0.0;
    double sumRatio = 1.0;
};
RelativeColorError relativeColorError(const Image& actual, const Image& reference);

// relativeColorError over blocks of `block` x `block` pixels, each averaged
// (BoxDownsample.h; pre-multiplied colours average correctly), the frame's
// last partial row and column of blocks left out. Against a path-traced
// reference the per-pixel error is mostly the tracer's own noise, which
// averaging over a block's N pixels divides by up to sqrt(N), while an
// error the approximation makes over a region stays: a block error above
// the reference's own (two seeds) is the approximation's. block 1 is
// relativeColorError; block < 1 throws std::invalid_argument.
RelativeColorError blockRelativeColorError(const Image& actual, const Image& reference, int block);

// An image to look at beside a failed comparison: each pixel's largest
// channel difference |actual - expected| times `gain`, as opaque grey,
// red where it is over the tolerance's outlier limit, so that moved edges
// and changed shades are told apart at a glance. Sizes must match.
Image differenceImage(const Image& actual, const Image& expected, const CoveredPixelTolerance& tolerance,
                      float gain = 10.0f);

}  // namespace hdhair
