#include "hdHair/image/ImageComparison.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "hdHair/image/BoxDownsample.h"

namespace hdhair {
namespace {

// Alpha above one 8-bit step: less is background that rounding or a
// straight-alpha PNG's arbitrary colour under alpha 0 may disturb.
constexpr float kCoveredAlpha = 1.0f / 255.0f;

bool covered(const Image& image, size_t pixel) {
    if (image.channels != 4) return true;
    float alpha = image.pixels[pixel * 4 + 3];
    return !(alpha <= kCoveredAlpha);  // NaN alpha counts as covered, so it is compared
}

std::string describe(const ImageComparison& c, const CoveredPixelTolerance& tolerance) {
    std::string verdict = c.passed ? "within tolerance" : "OUT OF TOLERANCE";
    std::string worst = c.worstChannel < 0
                            ? std::string("no covered pixel differs")
                            : fmt::format("worst ({}, {}) channel {}: {:.4f} vs {:.4f} expected", c.worstX, c.worstY,
                                          c.worstChannel, c.worstActual, c.worstExpected);
    return fmt::format(
        "{}: {} of {} covered pixels ({:.3f}%) differ by {:.4f} to {:.4f} (allowed {:.3f}%), {} by more (allowed "
        "{}); {}; mean {:.5f}, RMSE {:.5f}",
        verdict, c.pixelsOverThreshold, c.coveredPixels, 100.0 * c.shareOverThreshold, tolerance.threshold,
        tolerance.outlierLimit, 100.0 * tolerance.allowedShareOverThreshold, c.outliers, tolerance.allowedOutliers,
        worst, c.meanDifference, c.rootMeanSquare);
}

}  // namespace

CoveredPixelTolerance exactWithin(double limit) { return {limit, 0.0, limit, 0}; }

ImageComparison compareImages(const Image& actual, const Image& expected, const CoveredPixelTolerance& tolerance) {
    ImageComparison result;
    result.sizesMatch =
        actual.width == expected.width && actual.height == expected.height && actual.channels == expected.channels &&
        actual.pixels.size() == size_t(actual.width) * size_t(actual.height) * size_t(actual.channels) &&
        expected.pixels.size() == actual.pixels.size();
    if (!result.sizesMatch) {
        result.description = fmt::format("OUT OF TOLERANCE: sizes differ: {}x{}x{} vs {}x{}x{} expected", actual.width,
                                         actual.height, actual.channels, expected.width, expected.height,
                                         expected.channels);
        return result;
    }
    const size_t channels = size_t(actual.channels);
    const size_t pixels = size_t(actual.width) * size_t(actual.height);
    double sum = 0.0, sumSquares = 0.0;
    for (size_t p = 0; p < pixels; ++p) {
        if (!covered(actual, p) && !covered(expected, p)) continue;
        ++result.coveredPixels;
        double pixelDifference = 0.0;
        for (size_t c = 0; c < channels; ++c) {
            float a = actual.pixels[p * channels + c], b = expected.pixels[p * channels + c];
            // A NaN or infinity is as different as it gets.
            double d = (std::isfinite(a) && std::isfinite(b)) ? std::abs(double(a) - double(b)) : INFINITY;
            sum += d;
            sumSquares += d * d;
            pixelDifference = std::max(pixelDifference, d);
            if (d > result.maxDifference) {
                result.maxDifference = d;
                result.worstX = int(p % size_t(actual.width));
                result.worstY = int(p / size_t(actual.width));
                result.worstChannel = int(c);
                result.worstActual = a;
                result.worstExpected = b;
            }
        }
        if (pixelDifference > tolerance.outlierLimit)
            ++result.outliers;
        else if (pixelDifference > tolerance.threshold)
            ++result.pixelsOverThreshold;
    }
    if (result.coveredPixels > 0) {
        double samples = double(result.coveredPixels * channels);
        result.meanDifference = sum / samples;
        result.rootMeanSquare = std::sqrt(sumSquares / samples);
        result.shareOverThreshold = double(result.pixelsOverThreshold) / double(result.coveredPixels);
    }
    result.passed = result.shareOverThreshold <= tolerance.allowedShareOverThreshold &&
                    result.outliers <= tolerance.allowedOutliers;
    result.description = describe(result, tolerance);
    return result;
}

RelativeColorError relativeColorError(const Image& actual, const Image& reference) {
    if (actual.width != reference.width || actual.height != reference.height || actual.channels != reference.channels ||
        actual.pixels.size() != reference.pixels.size())
        throw std::invalid_argument("relativeColorError: the images' sizes differ");
    const size_t channels = size_t(actual.channels);
    const size_t colorChannels = channels == 4 ? 3 : channels;
    const size_t pixels = size_t(actual.width) * size_t(actual.height);
    RelativeColorError error;
    double differenceSquares = 0.0, referenceSquares = 0.0, largestDifference = 0.0, largestReference = 0.0;
    double actualSum = 0.0, referenceSum = 0.0;
    for (size_t p = 0; p < pixels; ++p) {
        if (!covered(actual, p) && !covered(reference, p)) continue;
        ++error.coveredPixels;
        for (size_t c = 0; c < colorChannels; ++c) {
            const double a = actual.pixels[p * channels + c], b = reference.pixels[p * channels + c];
            const double d = std::isfinite(a) && std::isfinite(b) ? std::abs(a - b) : INFINITY;
            differenceSquares += d * d;
            referenceSquares += b * b;
            actualSum += a;
            referenceSum += b;
            largestDifference = std::max(largestDifference, d);
            largestReference = std::max(largestReference, std::abs(b));
        }
    }
    if (error.coveredPixels == 0) return error;
    error.rootMeanSquare = referenceSquares > 0.0 ? std::sqrt(differenceSquares / referenceSquares)
                                                  : (differenceSquares > 0.0 ? INFINITY : 0.0);
    error.sumRatio = referenceSum != 0.0 ? actualSum / referenceSum : (actualSum == 0.0 ? 1.0 : INFINITY);
    error.largest = largestReference > 0.0 ? largestDifference / largestReference
                                           : (largestDifference > 0.0 ? INFINITY : 0.0);
    return error;
}

namespace {

// The image's top-left whole blocks.
Image croppedToBlocks(const Image& image, int block) {
    Image cropped(image.width / block * block, image.height / block * block, image.channels);
    const size_t channels = size_t(image.channels), row = size_t(cropped.width) * channels;
    for (int y = 0; y < cropped.height; ++y)
        std::copy_n(image.pixels.begin() + std::ptrdiff_t(size_t(y) * size_t(image.width) * channels), row,
                    cropped.pixels.begin() + std::ptrdiff_t(size_t(y) * row));
    return cropped;
}

}  // namespace

RelativeColorError blockRelativeColorError(const Image& actual, const Image& reference, int block) {
    if (block < 1) throw std::invalid_argument("blockRelativeColorError: the block must be at least one pixel");
    if (block == 1) return relativeColorError(actual, reference);
    if (actual.width != reference.width || actual.height != reference.height || actual.channels != reference.channels)
        throw std::invalid_argument("blockRelativeColorError: the images' sizes differ");
    return relativeColorError(boxDownsample(croppedToBlocks(actual, block), block),
                              boxDownsample(croppedToBlocks(reference, block), block));
}

Image differenceImage(const Image& actual, const Image& expected, const CoveredPixelTolerance& tolerance, float gain) {
    Image difference(actual.width, actual.height, 4);
    if (actual.width != expected.width || actual.height != expected.height || actual.channels != expected.channels)
        return difference;
    const size_t channels = size_t(actual.channels);
    const size_t pixels = size_t(actual.width) * size_t(actual.height);
    for (size_t p = 0; p < pixels; ++p) {
        float largest = 0.0f;
        const bool anyCovered = covered(actual, p) || covered(expected, p);
        for (size_t c = 0; anyCovered && c < channels; ++c) {
            const float d = std::fabs(actual.pixels[p * channels + c] - expected.pixels[p * channels + c]);
            largest = std::isnan(d) ? INFINITY : std::max(largest, d);
        }
        float* out = difference.pixels.data() + 4 * p;
        const float grey = std::min(1.0f, largest * gain);
        const bool outlier = double(largest) > tolerance.outlierLimit;
        out[0] = outlier ? 1.0f : grey;
        out[1] = outlier ? 0.0f : grey;
        out[2] = outlier ? 0.0f : grey;
        out[3] = 1.0f;
    }
    return difference;
}

}  // namespace hdhair
