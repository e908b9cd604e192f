#include "hdHair/image/BoxDownsample.h"

#include <stdexcept>

#include <fmt/format.h>

namespace hdhair {

Image boxDownsample(const Image& image, int factor) {
    if (factor < 1 || image.width % factor != 0 || image.height % factor != 0)
        throw std::invalid_argument(fmt::format("cannot box-downsample a {}x{} image by {}", image.width,
                                                image.height, factor));
    Image result(image.width / factor, image.height / factor, image.channels);
    const double weight = 1.0 / double(factor * factor);
    for (int y = 0; y < result.height; ++y)
        for (int x = 0; x < result.width; ++x)
            for (int c = 0; c < image.channels; ++c) {
                double sum = 0.0;
                for (int dy = 0; dy < factor; ++dy)
                    for (int dx = 0; dx < factor; ++dx) sum += image.at(x * factor + dx, y * factor + dy, c);
                result.at(x, y, c) = float(sum * weight);
            }
    return result;
}

}  // namespace hdhair
