#include "hdHair/plan/CameraView.h"

#include <algorithm>
#include <cmath>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/matrix_inverse.hpp>

namespace hdhair {

namespace {

// GfCamera::APERTURE_UNIT: apertures are in tenths of a scene unit.
constexpr double kApertureUnit = 0.1;
// GfCamera's default clipping range starts at 1; usdrecord's framing camera
// backs away by this much when it would be closer (see framingCamera).
constexpr double kDefaultNearClip = 1.0;

// CameraUtilConformedWindow(GfMatrix4d, CameraUtilFit, targetAspect)
// (pxr/imaging/cameraUtil/conformWindow.cpp), which Storm applies through
// CameraUtilFraming::ApplyToProjectionMatrix. glm's m[i][j] holds the same
// number as GfMatrix4d's m[i][j] for the same transform (one is the other's
// transpose, and glm indexes column first), so the code reads alike. The
// window is widened (or heightened) by scaling that axis of the projection,
// which scales the window about the optical axis, offsets included.
glm::dmat4 conformFit(glm::dmat4 projection, double targetAspect) {
    const double windowAspect =
        projection[0][0] != 0.0 ? projection[1][1] / projection[0][0] : 1.0;
    // Fit keeps the whole original window: a window wider than the target
    // keeps its width and grows in height, a narrower one grows in width.
    if (windowAspect > targetAspect) {
        const double old = projection[1][1];
        projection[1][1] = projection[0][0] * targetAspect;
        const double scale = old != 0.0 ? projection[1][1] / old : 1.0;
        projection[2][1] *= scale;
        projection[3][1] *= scale;
    } else {
        const double old = projection[0][0];
        projection[0][0] = targetAspect != 0.0 ? projection[1][1] / targetAspect : projection[1][1];
        const double scale = old != 0.0 ? projection[0][0] / old : 1.0;
        projection[2][0] *= scale;
        projection[3][0] *= scale;
    }
    return projection;
}

}  // namespace

glm::dvec3 CameraView::position() const { return glm::dvec3(glm::inverse(view)[3]); }

glm::dvec3 CameraView::forward() const {
    return glm::normalize(glm::dvec3(glm::inverse(view) * glm::dvec4(0.0, 0.0, -1.0, 0.0)));
}

glm::dvec3 CameraView::worldToPixel(const glm::dvec3& world) const {
    glm::dvec4 clip = projection * view * glm::dvec4(world, 1.0);
    glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
    return glm::dvec3((ndc.x + 1.0) * 0.5 * imageWidth, (1.0 - ndc.y) * 0.5 * imageHeight,
                      (ndc.z + 1.0) * 0.5);
}

int imageHeightFor(int imageWidth, float horizontalAperture, float verticalAperture) {
    // GfCamera::GetAspectRatio and UsdAppUtilsFrameRecorder::Record, in float
    // as there, so that the row count agrees with usdrecord's.
    float aspect = verticalAperture == 0.0f ? 0.0f : horizontalAperture / verticalAperture;
    if (std::fabs(aspect) < 1e-4f) aspect = 1.0f;
    float height = static_cast<float>(imageWidth) / aspect;
    return std::max(1, height >= 1.0f ? static_cast<int>(height) : 1);
}

CameraView cameraViewFromPrim(const CameraPrim& camera, int imageWidth) {
    CameraView result;
    result.imageWidth = std::max(1, imageWidth);
    result.imageHeight =
        imageHeightFor(result.imageWidth, camera.horizontalAperture, camera.verticalAperture);
    result.orthographic = camera.projection == Projection::Orthographic;
    result.nearClip = camera.clippingRange.x;
    result.farClip = camera.clippingRange.y;
    // Storm's world-to-view matrix is the inverse of the camera's transform,
    // scale included (HdRenderPassState::GetWorldToViewMatrix).
    result.view = glm::inverse(camera.worldTransform);

    // GfCamera::GetFrustum: the window is the aperture rectangle centred on
    // the aperture offsets, on the plane at unit distance for perspective
    // (scaled by 1 / focal length, both in the same unit) and in scene units
    // for orthographic (scaled by the aperture unit, a tenth).
    const double scale = result.orthographic
                             ? kApertureUnit
                             : (camera.focalLength != 0.0f ? 1.0 / camera.focalLength : 1.0);
    const double halfWidth = 0.5 * static_cast<double>(camera.horizontalAperture);
    const double halfHeight = 0.5 * static_cast<double>(camera.verticalAperture);
    const double left = scale * (camera.horizontalApertureOffset - halfWidth);
    const double right = scale * (camera.horizontalApertureOffset + halfWidth);
    const double bottom = scale * (camera.verticalApertureOffset - halfHeight);
    const double top = scale * (camera.verticalApertureOffset + halfHeight);
    const double n = result.nearClip, f = result.farClip;
    // GfFrustum::ComputeProjectionMatrix builds OpenGL's glOrtho / glFrustum
    // matrices (right-handed, depth to [-1, 1]); the perspective window on
    // the near plane is the unit-distance window times near.
    glm::dmat4 projection =
        result.orthographic ? glm::orthoRH_NO(left, right, bottom, top, n, f)
                            : glm::frustumRH_NO(left * n, right * n, bottom * n, top * n, n, f);
    result.projection = conformFit(
        projection, static_cast<double>(result.imageWidth) / result.imageHeight);
    return result;
}

CameraPrim framingCamera(const glm::dvec3& boundsMin, const glm::dvec3& boundsMax,
                         UpAxis upAxis, FramingStyle style) {
    glm::dvec3 lo = boundsMin, hi = boundsMax;
    if (lo.x > hi.x || lo.y > hi.y || lo.z > hi.z) {
        lo = glm::dvec3(-0.5);
        hi = glm::dvec3(0.5);
    }
    CameraPrim camera;  // the UsdGeomCamera / GfCamera defaults: 50, 20.955 x 15.2908
    camera.path = "/__hdHairFramingCamera";
    const glm::dvec3 center = 0.5 * (lo + hi);
    const glm::dvec3 size = hi - lo;
    // Extents across the image (x, up) and along the view, per up axis.
    const double width = size.x;
    const double height = upAxis == UpAxis::Y ? size.y : size.z;
    const double depth = upAxis == UpAxis::Y ? size.z : size.y;
    const double tanHalfH = camera.horizontalAperture / (2.0 * camera.focalLength);
    const double tanHalfV = camera.verticalAperture / (2.0 * camera.focalLength);

    double distance;
    if (style == FramingStyle::UsdRecord) {
        // _ComputeCameraToFrameStage: the focal plane goes through the front
        // face, at the distance where the half-diagonal of that face spans
        // half the horizontal field of view.
        const double planeRadius = std::sqrt(0.25 * width * width + 0.25 * height * height);
        distance = planeRadius / tanHalfH + 0.5 * depth;
        if (distance < kDefaultNearClip) distance += kDefaultNearClip;
    } else {
        // The nearest corners (on the front face) bound the distance: each
        // must lie within both half-angles of the lens.
        double front = std::max(0.5 * width / tanHalfH, 0.5 * height / tanHalfV);
        if (front <= 0.0) front = glm::length(size) > 0.0 ? 1e-3 * glm::length(size) : 1.0;
        distance = front + 0.5 * depth;
    }

    // Y-up: the camera's default orientation already looks down -Z with +Y
    // up. Z-up: usdrecord rotates it 90 degrees about X, so it looks down +Y
    // with +Z up, and moves it back along -Y.
    if (upAxis == UpAxis::Y) {
        camera.worldTransform = glm::translate(glm::dmat4(1.0), center + glm::dvec3(0, 0, distance));
    } else {
        camera.worldTransform =
            glm::translate(glm::dmat4(1.0), center + glm::dvec3(0, -distance, 0)) *
            glm::rotate(glm::dmat4(1.0), glm::radians(90.0), glm::dvec3(1, 0, 0));
    }

    // Everything framed lies within the bounding sphere, so its depth is
    // within distance -/+ radius; 1% margins keep the bounds' own surface
    // off the clipping planes.
    const double radius = 0.5 * glm::length(size);
    const double farClip = 1.01 * (distance + radius);
    const double nearClip = std::max(0.99 * (distance - radius), 1e-4 * farClip);
    camera.clippingRange = glm::vec2(static_cast<float>(nearClip), static_cast<float>(farClip));
    return camera;
}

CameraView frameBounds(const glm::dvec3& boundsMin, const glm::dvec3& boundsMax, UpAxis upAxis,
                       int imageWidth, FramingStyle style) {
    return cameraViewFromPrim(framingCamera(boundsMin, boundsMax, upAxis, style), imageWidth);
}

}  // namespace hdhair
