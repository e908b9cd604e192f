#pragma once
// Numeric VtValues as the engine's flat float arrays. Hydra hands primvars
// over as whatever the scene delegate holds: float, double or half, scalars
// or arrays, of 1 to 4 components (UsdImaging: VtVec3fArray points and
// colours, VtFloatArray widths; procedurals may send doubles or halves).

#include <string>
#include <vector>

#include "pxr/base/vt/value.h"

PXR_NAMESPACE_OPEN_SCOPE

struct HdHairFloats {
    std::vector<float> values;   // element-major
    int tupleSize = 1;
    std::string typeName;        // the held type, for messages
};

// False for a non-numeric value (strings, tokens, matrices, ...).
bool HdHairToFloats(VtValue const& value, HdHairFloats* out);

// An int array (indices, counts) from any integral array value.
bool HdHairToInts(VtValue const& value, std::vector<int>* out);

PXR_NAMESPACE_CLOSE_SCOPE
