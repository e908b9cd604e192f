#pragma once
// A value as written in a .usda file. Numeric types of every shape (scalars,
// vectors, quaternions, matrices and their arrays) are flattened into doubles
// with a tuple size; token, string and asset values are kept as strings.
// This covers every attribute type hair stages use without a type per shape.

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

    bool isNumeric() const { return strings.empty() && !isStringType(); }
    bool isStringType() const;         // token, string or asset (array or not)
    size_t elementCount() const {
        return isStringType() ? strings.size()
                              : (tupleSize > 0 ? numbers.size() / size_t(tupleSize) : 0);
    }
};

// Components per element for a scalar type name without [] ("float3" -> 3,
// "matrix4d" -> 16, "quatf" -> 4, "token" -> 1). Returns 0 for an unknown type.
int tupleSizeOf(const std::string& scalarTypeName);

}  // namespace hdhair::usda
