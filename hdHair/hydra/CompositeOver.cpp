#include "hdHair/hydra/CompositeOver.h"

namespace hdhair::hydra {

void compositeOver(Image& image, const glm::vec4& background) {
    if (image.channels != 4 || background == glm::vec4(0.0f)) return;
    for (size_t p = 0; p + 3 < image.pixels.size(); p += 4) {
        float remaining = 1.0f - image.pixels[p + 3];
        for (size_t c = 0; c < 4; ++c) image.pixels[p + c] += remaining * background[int(c)];
    }
}

}  // namespace hdhair::hydra
