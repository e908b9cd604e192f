#include "hdHair/usda/XformOps.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "hdHair/base/InputError.h"

namespace hdhair::usda {

namespace {

const char* const kInvertPrefix = "!invert!";
const char* const kResetXformStack = "!resetXformStack!";
const char* const kOpNamespace = "xformOp:";

bool startsWith(const std::string& text, const std::string& prefix) {
    return text.compare(0, prefix.size(), prefix) == 0;
}

glm::dmat4 rotateAbout(int axis, double degrees) {
    glm::dvec3 direction(0.0);
    direction[axis] = 1.0;
    return glm::rotate(glm::dmat4(1.0), glm::radians(degrees), direction);
}

// "XYZ" -> {0, 1, 2}; the letters name the order in which the rotations are
// applied to points (UsdGeomXformOp: "rotateXYZ ... first rotate about X,
// then Y, then Z").
bool parseRotationOrder(const std::string& letters, int order[3]) {
    if (letters.size() != 3) return false;
    bool seen[3] = {false, false, false};
    for (int i = 0; i < 3; ++i) {
        int axis = letters[static_cast<size_t>(i)] - 'X';
        if (axis < 0 || axis > 2 || seen[axis]) return false;
        seen[axis] = true;
        order[i] = axis;
    }
    return true;
}

// The op name's type: "xformOp:rotateXYZ:spin" -> "rotateXYZ".
std::string opTypeOf(const std::string& attributeName) {
    std::string rest = attributeName.substr(std::char_traits<char>::length(kOpNamespace));
    size_t colon = rest.find(':');
    return colon == std::string::npos ? rest : rest.substr(0, colon);
}

std::string location(const Prim& prim) {
    return prim.location.toString() + ": " + prim.path;
}

}  // namespace

size_t opValueCount(const std::string& opType) {
    int order[3];
    if (opType == "translate" || opType == "scale") return 3;
    if (opType == "rotateX" || opType == "rotateY" || opType == "rotateZ") return 1;
    if (startsWith(opType, "rotate") && parseRotationOrder(opType.substr(6), order)) return 3;
    if (opType == "orient") return 4;
    if (opType == "transform") return 16;
    return 0;
}

bool xformOpMatrix(const std::string& opType, const std::vector<double>& values,
                   glm::dmat4* out) {
    const glm::dmat4 identity(1.0);
    size_t count = opValueCount(opType);
    if (count == 0 || values.size() != count) return false;
    if (opType == "translate" || opType == "scale") {
        glm::dvec3 v(values[0], values[1], values[2]);
        *out = opType == "translate" ? glm::translate(identity, v) : glm::scale(identity, v);
        return true;
    }
    if (opType == "rotateX" || opType == "rotateY" || opType == "rotateZ") {
        *out = rotateAbout(opType.back() - 'X', values[0]);
        return true;
    }
    if (startsWith(opType, "rotate")) {
        int order[3];
        parseRotationOrder(opType.substr(6), order);
        // Column vectors: the rotation applied first stands rightmost. The
        // angles are indexed by axis (x, y, z) whatever the order.
        glm::dmat4 m(1.0);
        for (int axis : order) m = rotateAbout(axis, values[static_cast<size_t>(axis)]) * m;
        *out = m;
        return true;
    }
    if (opType == "orient") {
        // .usda writes quaternions real part first: (w, x, y, z); glm::dquat's
        // constructor takes (w, x, y, z) too.
        glm::dquat q(values[0], values[1], values[2], values[3]);
        double length = glm::length(q);
        *out = length > 0.0 ? glm::mat4_cast(q / length) : identity;
        return true;
    }
    // "transform": a .usda matrix is written row by row for row vectors,
    // translation in the last row; the column-vector matrix is its transpose,
    // which is exactly what reading the same 16 numbers column by column gives.
    *out = glm::make_mat4(values.data());
    return true;
}

LocalTransform computeLocalTransform(const Prim& prim, double time) {
    LocalTransform result;
    const Attribute* orderAttribute = prim.attribute("xformOpOrder");
    if (!orderAttribute) return result;
    std::optional<Value> orderValue = orderAttribute->valueAt(time);
    if (!orderValue || orderValue->isBlocked) return result;
    if (!orderValue->isStringType()) {
        throw InputError(orderAttribute->location.toString() + ": " + prim.path +
                         ".xformOpOrder: expected token[], found " + orderValue->typeName);
    }
    const std::vector<std::string>& order = orderValue->strings;

    // Walk from the last op to the first as UsdGeomXformable does: stop at
    // the last "!resetXformStack!", and skip adjacent pairs that are each
    // other's inverse ("xformOp:translate:pivot" next to its "!invert!"),
    // which cancel whether or not the attribute has a value.
    const std::string invertPrefix = kInvertPrefix;
    for (size_t i = order.size(); i-- > 0;) {
        const std::string& opName = order[i];
        if (i > 0) {
            const std::string& previous = order[i - 1];
            if (invertPrefix + opName == previous || invertPrefix + previous == opName) {
                --i;
                continue;
            }
        }
        if (opName == kResetXformStack) {
            result.resetsXformStack = true;
            break;
        }
        bool inverse = startsWith(opName, invertPrefix);
        std::string attributeName = inverse ? opName.substr(invertPrefix.size()) : opName;
        if (!startsWith(attributeName, kOpNamespace)) {
            throw InputError(location(prim) + ": xformOpOrder names '" + opName +
                             "', which is not an xformOp (expected \"xformOp:<type>\")");
        }
        const Attribute* attribute = prim.attribute(attributeName);
        if (!attribute) {
            throw InputError(location(prim) + ": xformOpOrder names '" + opName +
                             "' but the prim has no attribute '" + attributeName + "'");
        }
        std::optional<Value> value = attribute->valueAt(time);
        if (!value || value->isBlocked) continue;
        std::string opType = opTypeOf(attributeName);
        glm::dmat4 opMatrix;
        if (opValueCount(opType) == 0) {
            throw InputError(attribute->location.toString() + ": " + prim.path + "." +
                             attributeName + ": unknown xformOp type '" + opType + "'");
        }
        if (!value->isNumeric() || !xformOpMatrix(opType, value->numbers, &opMatrix)) {
            throw InputError(attribute->location.toString() + ": " + prim.path + "." +
                             attributeName + ": cannot use a value of type " +
                             value->typeName + " as an xformOp of type '" + opType + "'");
        }
        if (inverse) opMatrix = glm::inverse(opMatrix);
        result.matrix = opMatrix * result.matrix;
    }
    return result;
}

}  // namespace hdhair::usda
