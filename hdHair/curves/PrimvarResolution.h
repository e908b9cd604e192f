#pragma once
// Primvar resolution: the one place where an authored primvar (or one handed
// over by Hydra) is checked against the curves' topology and repaired. Every
// front end (the .usda reader's scene, the Hydra plugin) goes through here, so
// a given input resolves the same way everywhere. The rules mirror HdSt's
// HdSt_BasisCurvesPrimvarInterpolaterComputation (pxr/imaging/hdSt/
// basisCurvesComputations.cpp) and are listed in hdHair/curves/README.md.

#include <string>
#include <vector>

#include "hdHair/curves/CurveTopology.h"
#include "hdHair/scene/PrimvarFlattening.h"

namespace hdhair {

class Diagnostics;

// Curves resolve to exactly as many elements as their interpolation needs:
//  - Constant: 1;
//  - Uniform: one per curve (topology.curveCount());
//  - Varying: one per span end, topology.spanEndTotal() (= USD's varying
//    count, except pinned bspline/catmullRom curves, which get n values per
//    curve: authored nonperiodic-size data is padded by repeating its end
//    values, as HdsiPinnedCurveExpandingSceneIndex does);
//  - Vertex: one per vertex, topology.vertexTotal().
// FaceVarying never appears in a ResolvedPrimvar of curves: it resolves as Varying.

// Resolves `primvar` against `topology`. `fallback` is one element (its size
// is the expected tuple size). Never reads out of bounds and never throws:
//  - indices are followed; an out-of-range index gives the fallback for that
//    element;
//  - faceVarying is treated as varying;
//  - one element authored without interpolation metadata, or vertex, varying
//    or uniform data of size 1, is constant; constant data with more than one
//    element keeps its first;
//  - indexed vertex data with more elements than vertices is truncated;
//  - varying data may also have n values per pinned bspline/catmullRom curve,
//    or n+1 per linear periodic curve (UsdGeom's _ComputeVaryingDataSize);
//  - any other count, or a tuple size other than fallback.size(), resolves to
//    the constant fallback;
//  - a non-finite element is replaced by the fallback.
// Each repair is reported to `diagnostics` at "<primPath>.<attributeName>",
// e.g. "vertex interpolation needs 12 values, found 7; using the fallback (0.5, 0.5, 0.5)".
ResolvedPrimvar resolvePrimvar(const Primvar& primvar, const CurveTopology& topology,
                               const std::vector<float>& fallback, const std::string& primPath,
                               const std::string& primvarName, Diagnostics& diagnostics);

// Resolves prim.primvars[name] when authored, else returns constantPrimvar(fallback).
ResolvedPrimvar resolvePrimvar(const CurvesPrim& prim, const CurveTopology& topology, const std::string& primvarName,
                               const std::vector<float>& fallback, Diagnostics& diagnostics);

}  // namespace hdhair
