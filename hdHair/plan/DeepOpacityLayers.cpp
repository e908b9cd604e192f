#include "hdHair/plan/DeepOpacityLayers.h"

#include <algorithm>

namespace hdhair {

std::vector<float> deepOpacityLayerBoundaries(int layers, ShadowLayerSpacing spacing) {
    layers = std::clamp(layers, 1, kMaxShadowLayers);
    std::vector<float> boundaries(size_t(layers), 1.0f);
    const double k = double(layers);
    for (int i = 1; i < layers; ++i) {
        const double layer = double(i);
        boundaries[size_t(i - 1)] = spacing == ShadowLayerSpacing::Linear
                                        ? float(layer * (layer + 1.0) / (k * (k + 1.0)))
                                        : float(layer / k);
    }
    return boundaries;
}

}  // namespace hdhair
