#pragma once
// hdHair's camera (CameraView: the frustum usdrecord's rules give, conformed
// to the image) as Blender's camera, so both renderers see the same pixels
// (docs/cycles-reference.md, "Camera").
//
// With sensor fit HORIZONTAL Blender measures the view by its width:
//  - perspective: horizontal field of view 2·atan(1/P₀₀) (P the GL
//    projection, column-major P[column][row]); the window's centre sits at
//    x = P[2][0]/P₀₀, y = P[2][1]/P₁₁ on the plane at unit distance, and
//    Blender's shifts are offsets in units of the window's width 2/P₀₀:
//    shift_x = P[2][0]/2, shift_y = P[2][1]·P₀₀/(2·P₁₁);
//  - orthographic: ortho_scale = 2/P₀₀ (the view's width in scene units),
//    centre x = −P[3][0]/P₀₀, so shift_x = −P[3][0]/2, shift_y = −P[3][1]·P₀₀/(2·P₁₁).
// The image height is CameraView's (usdrecord's truncation), so the vertical
// extent follows from the pixels' squareness, as in hdHair.

#include <glm/mat4x4.hpp>

namespace hdhair {

struct CameraView;

struct CyclesCamera {
    bool orthographic = false;
    glm::dmat4 cameraToWorld{1.0};  // rotation and translation; the camera looks down −Z, +Y up
    double angleX = 0.0;            // perspective: horizontal field of view (radians)
    double orthoScale = 1.0;        // orthographic: the view's width (scene units)
    double shiftX = 0.0, shiftY = 0.0;
    double clipStart = 0.1, clipEnd = 1000.0;
    int width = 1, height = 1;
};

CyclesCamera cyclesCamera(const CameraView& view);

}  // namespace hdhair
