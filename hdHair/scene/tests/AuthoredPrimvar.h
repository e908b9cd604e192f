#pragma once
// Tests build primvars as a reader would hand them over: authored, with an
// explicit interpolation. One place that does it for every test.

#include <string>
#include <utility>
#include <vector>

#include "hdHair/scene/Primvar.h"

namespace hdhair::test {

inline Primvar authoredPrimvar(const std::string& name, Interpolation interpolation, int tupleSize,
                               std::vector<float> values) {
    Primvar primvar;
    primvar.name = name;
    primvar.interpolation = interpolation;
    primvar.interpolationAuthored = true;
    primvar.tupleSize = tupleSize;
    primvar.values = std::move(values);
    return primvar;
}

}  // namespace hdhair::test
