#pragma once
// A primvar as authored (or as Hydra hands it over): values, interpolation,
// optional indices. Every numeric primvar type (float, float3, color3f,
// normal3f, int, ...) is stored as a flat float array with a tuple size, so a
// single resolution path serves them all (hdHair/curves/PrimvarResolution.h).

#include <array>
#include <string>
#include <tuple>
#include <vector>

#include "hdHair/base/TokenTable.h"

namespace hdhair {

// USD's interpolation tokens (UsdGeomTokens). FaceVarying is accepted on input
// and treated as varying on curves, as Storm does.
enum class Interpolation { Constant, Uniform, Varying, Vertex, FaceVarying };

template <>
struct TokenTable<Interpolation> {
    static constexpr std::array<TokenName<Interpolation>, 5> names{{
         {Interpolation::Constant, "constant"},
         {Interpolation::Uniform, "uniform"},
         {Interpolation::Varying, "varying"},
         {Interpolation::Vertex, "vertex"},
         {Interpolation::FaceVarying, "faceVarying"}}};
};

struct Primvar {
    std::string name;                 // without the "primvars:" prefix, e.g. "displayColor"
    std::string typeName;             // USD type name as authored, e.g. "color3f[]"
    int tupleSize = 1;                // components per element (3 for color3f)
    std::vector<float> values;        // element-major: values[i * tupleSize + c]
    std::vector<int> indices;         // primvars:NAME:indices, empty when not indexed
    Interpolation interpolation = Interpolation::Constant;
    bool interpolationAuthored = false;  // false: the USD default for this primvar applied
    int elementSize = 1;              // USD elementSize metadata

    size_t elementCount() const {
        return tupleSize > 0 ? values.size() / static_cast<size_t>(tupleSize) : 0;
    }
    // Number of elements after indexing (indices.size() when indexed).
    size_t authoredCount() const { return indices.empty() ? elementCount() : indices.size(); }
    // Every member, for operator==: a scene keeps a prim's version when it is
    // set again unchanged (hdhair-record --frames), so nothing is prepared,
    // uploaded or shadowed again. A member added above must be added here;
    // the size check after the struct is there to say so.
    auto fields() const {
        return std::tie(name, typeName, tupleSize, values, indices, interpolation, interpolationAuthored, elementSize);
    }
    bool operator==(const Primvar& other) const { return fields() == other.fields(); }
    bool operator!=(const Primvar& other) const { return !(*this == other); }
};
static_assert(sizeof(Primvar) == 136, "a member was added to Primvar: add it to fields() too (x86-64 size)");

}  // namespace hdhair
