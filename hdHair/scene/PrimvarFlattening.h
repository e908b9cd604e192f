#pragma once
// The part of primvar resolution that does not depend on what the primvar
// lives on: checking the tuple size, following the indices, reading one
// element as constant, the constant case itself, the fallback with its
// warning, and replacing non-finite elements. Curves
// (hdHair/curves/PrimvarResolution.h) and meshes
// (hdHair/meshes/MeshPrimvarResolution.h) add their own element counts per
// interpolation on top, so a given input is repaired, and reported, the same
// way on both and from every front end.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "hdHair/scene/Primvar.h"

namespace hdhair {

class Diagnostics;

// Unauthored values: widths is Hydra's gprim fallback (VtFloatArray{1.0},
// UsdImaging gprimAdapter.cpp); displayColor and displayOpacity are the
// fallbacks UsdImaging reports when they are not authored.
inline const std::vector<float> kFallbackWidth{1.0f};
inline const std::vector<float> kFallbackDisplayColor{0.5f, 0.5f, 0.5f};
inline const std::vector<float> kFallbackDisplayOpacity{1.0f};

// A primvar with exactly as many elements as its interpolation needs on the
// prim it was resolved for (the counts are the curves' or the mesh's).
struct ResolvedPrimvar {
    Interpolation interpolation = Interpolation::Constant;
    int tupleSize = 1;
    std::vector<float> values;  // element-major

    size_t elementCount() const { return tupleSize > 0 ? values.size() / static_cast<size_t>(tupleSize) : 0; }
    const float* element(size_t i) const { return values.data() + i * static_cast<size_t>(tupleSize); }
};

// A constant primvar holding `value` (what an unauthored primvar resolves to).
ResolvedPrimvar constantPrimvar(const std::vector<float>& value);

// The attribute name as USD writes it, for messages: "widths" and "normals"
// are attributes on Curves/PointBased (whether authored as attributes or as
// primvars, prims store them under their bare name); every other name gets
// its "primvars:" namespace back.
std::string attributeName(const std::string& primvarName);

// "0.5" or "(0.5, 0.5, 0.5)", as the warnings print values.
std::string formatPrimvarValue(const std::vector<float>& value);

// The authored data flattened through its indices (UsdGeomPrimvar::
// ComputeFlattened), `fallback.size()` floats an element.
struct FlattenedPrimvar {
    // As authored, except that one element (HdSt treats vertex, varying and
    // uniform data of size 1 as constant, and one value without metadata can
    // only be constant) is Constant.
    Interpolation interpolation = Interpolation::Constant;
    std::vector<float> elements;
    size_t count = 0;      // elements.size() / tuple size
    bool indexed = false;  // the primvar had indices
};

// Warns and returns nullopt when the tuple size is not fallback.size() (the
// caller then uses the fallback); warns and ignores a partial last element;
// an out-of-range index gives the fallback for that element, with a warning.
// `where` is "<primPath>.<attributeName>".
std::optional<FlattenedPrimvar> flattenPrimvar(const Primvar& primvar, const std::vector<float>& fallback,
                                               const std::string& where, Diagnostics& diagnostics);

// Reports "<problem>; using the fallback <value>" at `where` and returns the
// constant fallback.
ResolvedPrimvar primvarFallback(const std::string& problem, const std::vector<float>& fallback,
                                const std::string& where, Diagnostics& diagnostics);

// The message for a count that does not match: "<authored> interpolation
// needs <expected> values<alternatives>, found <found>".
std::string primvarCountProblem(Interpolation authored, size_t expected, const std::string& alternatives,
                                size_t found);

// Constant data: its one element; the first of several, with a warning; the
// fallback when there is none.
ResolvedPrimvar resolveConstantPrimvar(FlattenedPrimvar flattened, Interpolation authored,
                                       const std::vector<float>& fallback, const std::string& where,
                                       Diagnostics& diagnostics);

// Replaces every element with a NaN or infinite component by the fallback,
// with one warning counting them.
void replaceNonFiniteElements(ResolvedPrimvar& resolved, const std::vector<float>& fallback, const std::string& where,
                              Diagnostics& diagnostics);

}  // namespace hdhair
