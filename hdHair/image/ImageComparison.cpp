#include "hdHair/image/ImageComparison.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace hdhair {

ImageDifference compareImages(const Image& actual, const Image& expected, double threshold) {
    ImageDifference result;
    result.sizesMatch = actual.width == expected.width && actual.height == expected.height &&
                        actual.channels == expected.channels;
    if (!result.sizesMatch) {
        result.maxDifference = result.meanDifference = result.rootMeanSquare = INFINITY;
        result.fractionOverThreshold = 1.0;
        return result;
    }
    size_t pixels = size_t(actual.width) * size_t(actual.height);
    size_t channels = size_t(actual.channels);
    double sum = 0.0, sumSquares = 0.0;
    size_t over = 0;
    for (size_t p = 0; p < pixels; ++p) {
        bool pixelOver = false;
        for (size_t c = 0; c < channels; ++c) {
            double a = actual.pixels[p * channels + c], b = expected.pixels[p * channels + c];
            // A NaN anywhere is as different as it gets.
            double d = (std::isfinite(a) && std::isfinite(b)) ? std::abs(a - b) : INFINITY;
            result.maxDifference = std::max(result.maxDifference, d);
            sum += d;
            sumSquares += d * d;
            pixelOver = pixelOver || d > threshold;
        }
        over += pixelOver ? 1 : 0;
    }
    double samples = double(std::max<size_t>(pixels * channels, 1));
    result.meanDifference = sum / samples;
    result.rootMeanSquare = std::sqrt(sumSquares / samples);
    result.fractionOverThreshold = double(over) / double(std::max<size_t>(pixels, 1));
    return result;
}

bool withinTolerance(const ImageDifference& difference, const ImageTolerance& tolerance) {
    return difference.sizesMatch && difference.fractionOverThreshold <= tolerance.allowedFraction &&
           difference.maxDifference <= tolerance.hardLimit;
}

std::string describe(const ImageDifference& difference, const ImageTolerance& tolerance) {
    if (!difference.sizesMatch) return "image sizes or channel counts differ";
    return fmt::format(
        "{:.3f}% of pixels differ by more than {:.4f} (allowed {:.3f}%), max difference {:.4f} "
        "(allowed {:.4f}), RMSE {:.5f}",
        100.0 * difference.fractionOverThreshold, tolerance.threshold, 100.0 * tolerance.allowedFraction,
        difference.maxDifference, tolerance.hardLimit, difference.rootMeanSquare);
}

}  // namespace hdhair
