#include "hdHair/usda/Value.h"

#include <cstring>

namespace hdhair::usda {

namespace {

struct TypeInfo {
    const char* name;
    int tupleSize;
    bool floating;
    int matrixDim;
    bool quaternion;
    bool stringType;
};

// Every scalar value type the reader accepts for attributes.
constexpr TypeInfo kTypes[] = {
    {"bool", 1, false, 0, false, false},
    {"uchar", 1, false, 0, false, false},
    {"int", 1, false, 0, false, false},
    {"uint", 1, false, 0, false, false},
    {"int64", 1, false, 0, false, false},
    {"uint64", 1, false, 0, false, false},
    {"half", 1, true, 0, false, false},
    {"float", 1, true, 0, false, false},
    {"double", 1, true, 0, false, false},
    {"timecode", 1, true, 0, false, false},
    {"string", 1, false, 0, false, true},
    {"token", 1, false, 0, false, true},
    {"asset", 1, false, 0, false, true},
    {"path", 1, false, 0, false, true},
    {"opaque", 1, false, 0, false, false},
    {"int2", 2, false, 0, false, false},
    {"int3", 3, false, 0, false, false},
    {"int4", 4, false, 0, false, false},
    {"half2", 2, true, 0, false, false},
    {"half3", 3, true, 0, false, false},
    {"half4", 4, true, 0, false, false},
    {"float2", 2, true, 0, false, false},
    {"float3", 3, true, 0, false, false},
    {"float4", 4, true, 0, false, false},
    {"double2", 2, true, 0, false, false},
    {"double3", 3, true, 0, false, false},
    {"double4", 4, true, 0, false, false},
    {"point3h", 3, true, 0, false, false},
    {"point3f", 3, true, 0, false, false},
    {"point3d", 3, true, 0, false, false},
    {"normal3h", 3, true, 0, false, false},
    {"normal3f", 3, true, 0, false, false},
    {"normal3d", 3, true, 0, false, false},
    {"vector3h", 3, true, 0, false, false},
    {"vector3f", 3, true, 0, false, false},
    {"vector3d", 3, true, 0, false, false},
    {"color3h", 3, true, 0, false, false},
    {"color3f", 3, true, 0, false, false},
    {"color3d", 3, true, 0, false, false},
    {"color4h", 4, true, 0, false, false},
    {"color4f", 4, true, 0, false, false},
    {"color4d", 4, true, 0, false, false},
    {"texCoord2h", 2, true, 0, false, false},
    {"texCoord2f", 2, true, 0, false, false},
    {"texCoord2d", 2, true, 0, false, false},
    {"texCoord3h", 3, true, 0, false, false},
    {"texCoord3f", 3, true, 0, false, false},
    {"texCoord3d", 3, true, 0, false, false},
    {"quath", 4, true, 0, true, false},
    {"quatf", 4, true, 0, true, false},
    {"quatd", 4, true, 0, true, false},
    {"matrix2d", 4, true, 2, false, false},
    {"matrix3d", 9, true, 3, false, false},
    {"matrix4d", 16, true, 4, false, false},
    {"frame4d", 16, true, 4, false, false},
};

const TypeInfo* lookup(const std::string& scalarTypeName) {
    for (const TypeInfo& info : kTypes) {
        if (scalarTypeName == info.name) return &info;
    }
    return nullptr;
}

// One field of a scalar type's TypeInfo; `unknown` for a type the reader does not accept.
template <class T>
T typeInfoField(const std::string& scalarTypeName, T TypeInfo::*field, T unknown) {
    const TypeInfo* info = lookup(scalarTypeName);
    return info ? info->*field : unknown;
}

}  // namespace

std::string scalarTypeNameOf(const std::string& typeName) {
    if (typeName.size() >= 2 && typeName.compare(typeName.size() - 2, 2, "[]") == 0) {
        return typeName.substr(0, typeName.size() - 2);
    }
    return typeName;
}

int tupleSizeOf(const std::string& scalarTypeName) {
    return typeInfoField(scalarTypeName, &TypeInfo::tupleSize, 0);
}

bool isFloatingPointType(const std::string& scalarTypeName) {
    return typeInfoField(scalarTypeName, &TypeInfo::floating, false);
}

int matrixDimensionOf(const std::string& scalarTypeName) {
    return typeInfoField(scalarTypeName, &TypeInfo::matrixDim, 0);
}

bool isQuaternionType(const std::string& scalarTypeName) {
    return typeInfoField(scalarTypeName, &TypeInfo::quaternion, false);
}

bool Value::isStringType() const {
    return typeInfoField(scalarTypeNameOf(typeName), &TypeInfo::stringType, false);
}

const Value* Value::find(const std::string& key) const {
    if (!isDictionary()) return nullptr;
    for (size_t i = 0; i < keys.size() && i < items.size(); ++i) {
        if (keys[i] == key) return &items[i];
    }
    return nullptr;
}

}  // namespace hdhair::usda
