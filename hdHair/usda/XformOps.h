#pragma once
// A prim's local transform from its xformOpOrder and xformOp:* attributes, as
// UsdGeomXformable::GetLocalTransformation computes it
// (pxr/usd/usdGeom/xformable.cpp, xformOp.cpp).
//
// Conventions. USD multiplies row vectors (p' = p * M) and builds the local
// matrix as M = op[N-1] * ... * op[1] * op[0]; in the column-vector
// convention that glm uses this is the transpose, local = op[0] * op[1] * ...
// * op[N-1]. Either way the LAST op in xformOpOrder is applied to points
// FIRST: xformOpOrder = ["xformOp:translate", "xformOp:rotateXYZ",
// "xformOp:scale"] scales, then rotates, then translates (the USD
// documentation's "translate, rotate, scale" example). Every matrix returned
// here is a glm (column-major, column-vector) matrix: p' = M * p.

#include <cstddef>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>

#include "hdHair/usda/Stage.h"

namespace hdhair::usda {

struct LocalTransform {
    glm::dmat4 matrix{1.0};         // local to parent space, column vectors
    bool resetsXformStack = false;  // "!resetXformStack!": parents' transforms are ignored
};

// Evaluates `xformOpOrder` of `prim` at `time` (Attribute::valueAt, so
// time-sampled ops animate). A prim without xformOpOrder has the identity.
//
// Semantics, following UsdGeomXformable:
//  - op names are "xformOp:<type>" or "xformOp:<type>:<suffix>" (the suffix
//    only makes the attribute name unique, e.g. "xformOp:translate:pivot");
//  - "!invert!xformOp:..." uses the inverse of that op's matrix;
//  - "!resetXformStack!" discards every op before it and sets resetsXformStack;
//  - rotate angles are in degrees, rotateXYZ rotates about X first, then Y,
//    then Z (likewise for the other orders); orient is a quaternion written
//    real part first and is normalised; transform is a matrix4d as written in
//    the file (row-vector, translation in the last row);
//  - an op attribute that exists but has no value at `time` (declared only,
//    or blocked with None) is the identity, as UsdGeomXformOp::GetOpTransform.
//
// Throws InputError ("file:line:col: /Prim: ...") when xformOpOrder names an
// attribute the prim does not have (USD itself only warns and skips the op;
// a stage whose transforms cannot be evaluated would render wrongly, so it is
// refused here), for an unknown op type, and for a value of the wrong shape.
LocalTransform computeLocalTransform(const Prim& prim, double time);

// How many numbers an op of this type takes (translate 3, rotateX 1,
// rotateZYX 3, orient 4, transform 16); 0 for an unknown op type.
size_t opValueCount(const std::string& opType);

// The matrix of one op: `opType` is "translate", "scale", "rotateX", ...,
// "orient" or "transform"; `values` are the attribute's numbers as Value
// stores them (3 for translate/scale/rotateXYZ..., 1 for rotateX/Y/Z, 4 for
// orient as (real, i, j, k), 16 row-major for transform). Returns false for
// an unknown op type or a wrong number of values.
bool xformOpMatrix(const std::string& opType, const std::vector<double>& values,
                   glm::dmat4* out);

}  // namespace hdhair::usda
