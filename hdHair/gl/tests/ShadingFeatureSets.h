#pragma once
// What the tests of shading feature sets share: failures that name the
// features, and a set made of the features listed.

#include <initializer_list>
#include <ostream>

#include "hdHair/gl/ShadingFeatures.h"

namespace hdhair::gl {

// Failures name the features, not the bytes.
inline void PrintTo(const ShadingFeatures& features, std::ostream* out) { *out << features.describe(); }

inline ShadingFeatures only(std::initializer_list<ShadingFeature> features) {
    ShadingFeatures set;
    for (ShadingFeature feature : features) set.add(feature);
    return set;
}

}  // namespace hdhair::gl
