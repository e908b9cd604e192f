#include "hdHair/hydra/VtValueConversion.h"

#include "pxr/base/gf/half.h"
#include "pxr/base/gf/vec2d.h"
#include "pxr/base/gf/vec2f.h"
#include "pxr/base/gf/vec2h.h"
#include "pxr/base/gf/vec3d.h"
#include "pxr/base/gf/vec3f.h"
#include "pxr/base/gf/vec3h.h"
#include "pxr/base/gf/vec4d.h"
#include "pxr/base/gf/vec4f.h"
#include "pxr/base/gf/vec4h.h"
#include "pxr/base/vt/array.h"
#include "pxr/base/vt/types.h"

PXR_NAMESPACE_OPEN_SCOPE

namespace {

template <typename Scalar>
float toFloat(Scalar s) {
    return static_cast<float>(s);
}

// Scalars and GfVec of any component type.
template <typename T>
void append(T const& element, std::vector<float>& out) {
    if constexpr (std::is_arithmetic_v<T> || std::is_same_v<T, GfHalf>) {
        out.push_back(toFloat(element));
    } else {
        for (size_t c = 0; c < T::dimension; ++c) out.push_back(toFloat(element[c]));
    }
}

template <typename T>
constexpr int tupleSizeOf() {
    if constexpr (std::is_arithmetic_v<T> || std::is_same_v<T, GfHalf>) return 1;
    else return int(T::dimension);
}

// Tries T and VtArray<T>; true when the value holds either.
template <typename T>
bool tryType(VtValue const& value, HdHairFloats* out) {
    if (value.IsHolding<VtArray<T>>()) {
        VtArray<T> const& array = value.UncheckedGet<VtArray<T>>();
        out->values.clear();
        out->values.reserve(array.size() * size_t(tupleSizeOf<T>()));
        for (T const& element : array) append(element, out->values);
        out->tupleSize = tupleSizeOf<T>();
        out->typeName = value.GetTypeName();
        return true;
    }
    if (value.IsHolding<T>()) {
        out->values.clear();
        append(value.UncheckedGet<T>(), out->values);
        out->tupleSize = tupleSizeOf<T>();
        out->typeName = value.GetTypeName();
        return true;
    }
    return false;
}

}  // namespace

bool HdHairToFloats(VtValue const& value, HdHairFloats* out) {
    return tryType<float>(value, out) || tryType<GfVec3f>(value, out) || tryType<double>(value, out) ||
           tryType<GfVec3d>(value, out) || tryType<GfHalf>(value, out) || tryType<GfVec3h>(value, out) ||
           tryType<GfVec2f>(value, out) || tryType<GfVec4f>(value, out) || tryType<GfVec2d>(value, out) ||
           tryType<GfVec4d>(value, out) || tryType<GfVec2h>(value, out) || tryType<GfVec4h>(value, out) ||
           tryType<int>(value, out) || tryType<bool>(value, out);
}

bool HdHairToInts(VtValue const& value, std::vector<int>* out) {
    if (value.IsHolding<VtIntArray>()) {
        VtIntArray const& array = value.UncheckedGet<VtIntArray>();
        out->assign(array.begin(), array.end());
        return true;
    }
    return false;
}

PXR_NAMESPACE_CLOSE_SCOPE
