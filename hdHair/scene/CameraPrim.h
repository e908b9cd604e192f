#pragma once
// A UsdGeomCamera: lens in USD's units (focal length and apertures in tenths
// of a scene unit, conventionally millimetres) and its world transform.

#include <string>
#include <tuple>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

namespace hdhair {

enum class Projection { Perspective, Orthographic };

struct CameraPrim {
    std::string path;
    Projection projection = Projection::Perspective;
    // UsdGeomCamera fallback values.
    float focalLength = 50.0f;
    float horizontalAperture = 20.955f;
    float verticalAperture = 15.2908f;
    float horizontalApertureOffset = 0.0f;
    float verticalApertureOffset = 0.0f;
    glm::vec2 clippingRange{1.0f, 1000000.0f};
    glm::dmat4 worldTransform{1.0};  // camera to world; the camera looks down -Z, +Y up
    // Every member, for operator==: a scene keeps a prim's version when it is
    // set again unchanged (hdhair-record --frames), so nothing is prepared,
    // uploaded or shadowed again. A member added above must be added here;
    // the size check after the struct is there to say so.
    auto fields() const {
        return std::tie(path, projection, focalLength, horizontalAperture, verticalAperture, horizontalApertureOffset,
                        verticalApertureOffset, clippingRange, worldTransform);
    }
    bool operator==(const CameraPrim& other) const { return fields() == other.fields(); }
    bool operator!=(const CameraPrim& other) const { return !(*this == other); }
};
static_assert(sizeof(CameraPrim) == 192, "a member was added to CameraPrim: add it to fields() too (x86-64 size)");

}  // namespace hdhair
