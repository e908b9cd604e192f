#pragma once
// An orthographic view for scenes built in code, so that where a strand
// lands follows from its world position by hand: the camera looks down -Z
// from z = 10 at a square `unitsAcross` world units wide centred on the
// origin, rendered `pixels` wide and high.

#include <glm/gtc/matrix_transform.hpp>

#include "hdHair/plan/CameraView.h"
#include "hdHair/scene/CameraPrim.h"

namespace hdhair::testenv {

inline CameraView orthographicView(double unitsAcross, int pixels) {
    CameraPrim camera;
    camera.projection = Projection::Orthographic;
    // Orthographic apertures are in tenths of a scene unit (GfCamera).
    camera.horizontalAperture = camera.verticalAperture = float(10.0 * unitsAcross);
    camera.clippingRange = {0.1f, 100.0f};
    camera.worldTransform = glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 0.0, 10.0));
    return cameraViewFromPrim(camera, pixels);
}

}  // namespace hdhair::testenv
