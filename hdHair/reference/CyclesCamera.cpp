#include "hdHair/reference/CyclesCamera.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "hdHair/plan/CameraView.h"

namespace hdhair {

CyclesCamera cyclesCamera(const CameraView& view) {
    CyclesCamera camera;
    const glm::dmat4& p = view.projection;
    camera.orthographic = view.orthographic;
    camera.width = view.imageWidth;
    camera.height = view.imageHeight;
    camera.clipStart = view.nearClip;
    camera.clipEnd = view.farClip;
    if (view.orthographic) {
        camera.orthoScale = 2.0 / p[0][0];
        camera.shiftX = -p[3][0] / 2.0;
        camera.shiftY = -p[3][1] * p[0][0] / (2.0 * p[1][1]);
    } else {
        camera.angleX = 2.0 * std::atan(1.0 / p[0][0]);
        camera.shiftX = p[2][0] / 2.0;
        camera.shiftY = p[2][1] * p[0][0] / (2.0 * p[1][1]);
    }
    // The view matrix may carry a camera prim's scale; Blender's camera takes
    // its lens from the parameters above, so only the rigid part is kept.
    const glm::dmat4 cameraToWorld = glm::inverse(view.view);
    for (int axis = 0; axis < 3; ++axis)
        camera.cameraToWorld[axis] = glm::dvec4(glm::normalize(glm::dvec3(cameraToWorld[axis])), 0.0);
    camera.cameraToWorld[3] = cameraToWorld[3];
    return camera;
}

}  // namespace hdhair
