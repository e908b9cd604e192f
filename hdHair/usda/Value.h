#pragma once
// A value as written in a .usda file. Numeric types of every shape (scalars,
// vectors, quaternions, matrices and their arrays) are flattened into doubles
// with a tuple size; token, string and asset values are kept as strings.
// This covers every attribute type hair stages use without a type per shape.
//
// Untyped metadata values (the reader's own additions, see README.md):
//   "dictionary"  customData = {...}: keys in `keys`, values in `items`
//   "path"        </World/a> (strings holds the path without the <>)
//   "list"        a heterogeneous metadata list: elements in `items`
//   "tuple"       a metadata tuple (1, 2, 3): numbers, tupleSize = count
//   "double"/"string"/"bool"/"token"/"asset" for bare metadata scalars,
//   "double[]"/"string[]"/... for homogeneous metadata lists.

#include <string>
#include <vector>

namespace hdhair::usda {

struct Value {
    std::string typeName;              // as declared, e.g. "float3[]", "token", "matrix4d"
    bool isArray = false;              // declared with []
    int tupleSize = 1;                 // components per element: 3 for float3, 16 for matrix4d
    std::vector<double> numbers;       // numeric types (bool as 0/1), element-major, row-major matrices
    std::vector<std::string> strings;  // token, string and asset types (assets without the @s)
    bool isBlocked = false;            // authored as None
    std::vector<std::string> keys;     // "dictionary": keys in authored order
    std::vector<Value> items;          // "dictionary": values parallel to keys; "list": elements

    bool isNumeric() const {
        return strings.empty() && items.empty() && !isStringType() && !isDictionary();
    }
    bool isStringType() const;         // token, string, asset or path (array or not)
    bool isDictionary() const { return typeName == "dictionary"; }
    // Dictionary lookup; nullptr when absent or not a dictionary.
    const Value* find(const std::string& key) const;
    // Convenience: the first string (token/string/asset/path) or "" when none.
    std::string stringOr(const std::string& fallback = std::string()) const {
        return strings.empty() ? fallback : strings.front();
    }
    // Convenience: the first number or `fallback` when none.
    double numberOr(double fallback = 0.0) const { return numbers.empty() ? fallback : numbers.front(); }
    size_t elementCount() const {
        return isStringType() ? strings.size()
                              : (tupleSize > 0 ? numbers.size() / size_t(tupleSize) : 0);
    }
};

// Components per element for a scalar type name without [] ("float3" -> 3,
// "matrix4d" -> 16, "quatf" -> 4, "token" -> 1). Returns 0 for an unknown type.
int tupleSizeOf(const std::string& scalarTypeName);

// "float3[]" -> "float3"; names without [] are returned unchanged.
std::string scalarTypeNameOf(const std::string& typeName);
// True for the types whose components are half/float/double/timecode (and
// their vector, point, color, quat, matrix, frame shapes): these interpolate
// linearly between time samples; everything else is held.
bool isFloatingPointType(const std::string& scalarTypeName);
// Rows of a square matrix type ("matrix4d" -> 4, "frame4d" -> 4), 0 otherwise.
int matrixDimensionOf(const std::string& scalarTypeName);
// True for quath/quatf/quatd (interpolated with slerp).
bool isQuaternionType(const std::string& scalarTypeName);

}  // namespace hdhair::usda
