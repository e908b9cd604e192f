#pragma once
// The camera math the renderer uses: view and projection matrices and the
// image size for a UsdGeomCamera, computed the way usdrecord and Storm do
// (GfCamera::GetFrustum, GfFrustum::ComputeProjectionMatrix, the image-height
// rule of UsdAppUtilsFrameRecorder::Record and the "fit" window policy of
// CameraUtilFraming), plus the camera usdrecord builds when it is given none.
//
// All matrices are glm (column-major, column vectors: p' = M * p). The
// projection is OpenGL's: clip-space depth in [-1, 1], as GfFrustum builds it.

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "hdHair/plan/SettingTokens.h"
#include "hdHair/scene/CameraPrim.h"
#include "hdHair/scene/Scene.h"

namespace hdhair {

struct CameraView {
    glm::dmat4 view{1.0};        // world to camera (inverse of CameraPrim::worldTransform)
    glm::dmat4 projection{1.0};  // camera to clip space
    int imageWidth = 1, imageHeight = 1;
    double nearClip = 1.0, farClip = 1000000.0;
    bool orthographic = false;

    // World point to pixel coordinates: x right, y DOWN from the top-left
    // corner, (0,0) the corner of the first pixel, (w,h) the opposite corner.
    // z is the window depth in [0, 1].
    glm::dvec3 worldToPixel(const glm::dvec3& world) const;

    glm::dvec3 position() const;  // the eye, in world space
    glm::dvec3 forward() const;   // the unit viewing direction (the camera's -Z), in world space
    // Pixels a world unit spans horizontally at clip w = 1: half the image
    // width times the projection's x scale (GL matrices: [0][0]).
    double pixelsPerUnit() const { return projection[0][0] * imageWidth * 0.5; }
};

// The image height usdrecord gives an image `imageWidth` pixels wide for a
// camera with these apertures (UsdAppUtilsFrameRecorder::Record):
// aspect = float(horizontalAperture / verticalAperture), 1 when it is close to
// 0; height = max(1, floor(float(imageWidth) / aspect)). Truncation, not
// rounding, is what usdrecord does: 960 pixels with the default 20.955 x
// 15.2908 apertures give 700 rows (700.51; rounding would give 701).
int imageHeightFor(int imageWidth, float horizontalAperture, float verticalAperture);

// The view of a camera prim rendered `imageWidth` pixels wide.
//
// Frustum (GfCamera::GetFrustum): the window is centred on the aperture
// offsets, window = (offset -/+ aperture / 2) * scale, where
//  - perspective: scale = 1 / focalLength, the window on the plane at unit
//    distance (apertures and focal length share a unit, so only their ratio
//    counts): at the near plane half the width is near * hAp / (2 * f) and an
//    offset moves the window by near * offset / f;
//  - orthographic: scale = 1/10, because apertures are in tenths of a scene
//    unit (GfCamera::APERTURE_UNIT): the view is hAp / 10 scene units wide.
// Near and far are the clippingRange. The window is then conformed to the
// image's aspect with CameraUtilFit (the window policy usdrecord uses): the
// truncated image height makes the image a little wider than the aperture,
// and the window grows about its centre in that direction to match, so
// pixels stay square and nothing the aperture shows is cut.
CameraView cameraViewFromPrim(const CameraPrim& camera, int imageWidth);

// How frameBounds places the camera: FramingStyle (SettingTokens.h, the framing setting).

// The camera for a stage rendered without a camera, as usdrecord builds it:
//  - lens: a default GfCamera / UsdGeomCamera: 50 focal length, 20.955 x
//    15.2908 apertures (a 23.7 degree horizontal field of view; the image is
//    20.955 / 15.2908 = 1.37 times as wide as high), perspective;
//  - Y-up: looking down -Z at the bounds' centre, +Y up; Z-up: rotated 90
//    degrees about X, looking down +Y with +Z up;
//  - distance from the centre (UsdRecord style): r / tan(hfov / 2) + d / 2,
//    with r the half-diagonal of the bounds' extent across the view (x and y
//    for Y-up, x and z for Z-up) and d the extent along the view (z for Y-up,
//    y for Z-up); if that is less than 1 (usdrecord's default near clip) 1 is
//    added, so that small bounds are not cut by that near plane;
//  - clipping range: usdrecord keeps GfCamera's default [1, 1e6]. That depth
//    range wastes depth-buffer precision, and the image only depends on it
//    when something is outside it, which cannot happen for the bounds framed;
//    so the range here is derived from the distance D to the centre and the
//    bounding sphere's radius R (half the bounds' diagonal), which contains
//    everything: far = 1.01 * (D + R), near = max(0.99 * (D - R), 1e-4 * far).
// Empty bounds (any min > max) frame the unit cube [-0.5, 0.5]^3.
CameraPrim framingCamera(const glm::dvec3& boundsMin, const glm::dvec3& boundsMax,
                         UpAxis upAxis, FramingStyle style = FramingStyle::UsdRecord);

// cameraViewFromPrim(framingCamera(...), imageWidth).
CameraView frameBounds(const glm::dvec3& boundsMin, const glm::dvec3& boundsMax,
                       UpAxis upAxis, int imageWidth,
                       FramingStyle style = FramingStyle::UsdRecord);

}  // namespace hdhair
