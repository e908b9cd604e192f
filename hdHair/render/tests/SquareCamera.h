#pragma once
// The render tests' camera: orthographic, looking down -Z from z = 5 at the
// square [-1.2, 1.2]² (every pixel sees the view direction +Z).

#include <glm/gtc/matrix_transform.hpp>

#include "hdHair/plan/CameraView.h"
#include "hdHair/scene/CameraPrim.h"

namespace hdhair::test {

inline CameraView squareCamera(int pixels) {
    CameraPrim camera;
    camera.projection = Projection::Orthographic;
    camera.horizontalAperture = camera.verticalAperture = 24.0f;  // tenths of a unit: 2.4 units
    camera.worldTransform = glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 0.0, 5.0));
    return cameraViewFromPrim(camera, pixels);
}

}  // namespace hdhair::test
