#pragma once
// A BasisCurves prim as the engine sees it: topology, points and primvars as
// authored, plus its world transform. Nothing here is resolved or validated:
// hdHair/curves/ does that, in one place, for every front end.

#include <array>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "hdHair/base/TokenTable.h"
#include "hdHair/scene/Primvar.h"

namespace hdhair {

enum class CurveType { Linear, Cubic };
enum class CurveBasis { Bezier, Bspline, CatmullRom };
enum class CurveWrap { Nonperiodic, Periodic, Pinned };

// USD's tokens for them (UsdGeomTokens), parsed and printed through base/TokenTable.h.
template <>
struct TokenTable<CurveType> {
    static constexpr std::array<TokenName<CurveType>, 2> names{{
         {CurveType::Linear, "linear"},
         {CurveType::Cubic, "cubic"}}};
};
template <>
struct TokenTable<CurveBasis> {
    static constexpr std::array<TokenName<CurveBasis>, 3> names{{
         {CurveBasis::Bezier, "bezier"},
         {CurveBasis::Bspline, "bspline"},
         {CurveBasis::CatmullRom, "catmullRom"}}};
};
template <>
struct TokenTable<CurveWrap> {
    static constexpr std::array<TokenName<CurveWrap>, 3> names{{
         {CurveWrap::Nonperiodic, "nonperiodic"},
         {CurveWrap::Periodic, "periodic"},
         {CurveWrap::Pinned, "pinned"}}};
};

struct CurvesPrim {
    std::string path;                       // "/World/hair"
    std::string sourceFile;                 // where it was read from, for messages ("" from Hydra)
    CurveType type = CurveType::Cubic;      // USD fallbacks: cubic, bezier, nonperiodic
    CurveBasis basis = CurveBasis::Bezier;
    CurveWrap wrap = CurveWrap::Nonperiodic;
    std::vector<int> curveVertexCounts;
    std::vector<glm::vec3> points;          // object space
    // "widths", "normals", "displayColor", "displayOpacity" and every other
    // primvar, keyed by name without "primvars:". Widths and normals are
    // stored here too, whether authored as attributes or as primvars.
    std::map<std::string, Primvar> primvars;
    glm::dmat4 worldTransform{1.0};
    bool visible = true;
    // Written to the primId output for picking: Hydra's HdRprim::GetPrimId().
    int primId = -1;
    // Written to the instanceId output: which instance of an instanced prim
    // this is (Hydra's instance index; 0 for a prim that is not instanced).
    int instanceId = 0;
    // Curves not drawn, by index (Hydra's HdBasisCurvesTopology invisible
    // curves). They keep their vertices and primvar elements, so the other
    // curves' data and elementIds do not shift.
    std::vector<int> invisibleCurves;
    // primvars:hdHair:shadingModel (HdHairAPI): "kajiyaKay", "marschner" or
    // "flat"; empty means the shadingModel render setting.
    std::string shadingModel;
    // The bound material's path (UsdShadeMaterialBindingAPI: the preview
    // purpose first, then all purposes, nearest ancestor first); "" when none.
    std::string materialBinding;

    const Primvar* findPrimvar(const std::string& name) const {
        auto it = primvars.find(name);
        return it == primvars.end() ? nullptr : &it->second;
    }
    // Every member, for operator==: a scene keeps a prim's version when it is
    // set again unchanged (hdhair-record --frames), so nothing is prepared,
    // uploaded or shadowed again. A member added above must be added here;
    // the size check after the struct is there to say so.
    auto fields() const {
        return std::tie(path, sourceFile, type, basis, wrap, curveVertexCounts, points, primvars, worldTransform, visible,
                        primId, instanceId, invisibleCurves, shadingModel, materialBinding);
    }
    bool operator==(const CurvesPrim& other) const { return fields() == other.fields(); }
    bool operator!=(const CurvesPrim& other) const { return !(*this == other); }
};
static_assert(sizeof(CurvesPrim) == 408, "a member was added to CurvesPrim: add it to fields() too (x86-64 size)");

}  // namespace hdhair
