#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "hdHair/plan/CameraView.h"

using namespace hdhair;

namespace {

// A lens chosen so that every number below can be checked by hand:
// tan(half horizontal fov) = 40 / (2 * 50) = 0.4, vertical 20 / 100 = 0.2.
CameraPrim handCamera() {
    CameraPrim camera;
    camera.path = "/cam";
    camera.focalLength = 50.0f;
    camera.horizontalAperture = 40.0f;
    camera.verticalAperture = 20.0f;
    camera.clippingRange = glm::vec2(1.0f, 100.0f);
    return camera;
}

void expectPixel(const CameraView& view, glm::dvec3 world, double x, double y) {
    glm::dvec3 pixel = view.worldToPixel(world);
    EXPECT_NEAR(pixel.x, x, 1e-6) << "world (" << world.x << ", " << world.y << ", " << world.z << ")";
    EXPECT_NEAR(pixel.y, y, 1e-6) << "world (" << world.x << ", " << world.y << ", " << world.z << ")";
}

std::vector<glm::dvec3> corners(glm::dvec3 lo, glm::dvec3 hi) {
    std::vector<glm::dvec3> result;
    for (int i = 0; i < 8; ++i)
        result.emplace_back(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
    return result;
}

bool inside(const CameraView& view, glm::dvec3 world) {
    glm::dvec3 p = view.worldToPixel(world);
    const double eps = 1e-6;
    return p.x >= -eps && p.x <= view.imageWidth + eps && p.y >= -eps &&
           p.y <= view.imageHeight + eps && p.z >= 0.0 && p.z <= 1.0;
}

}  // namespace

TEST(CameraView, PerspectiveProjectsKnownPointsToKnownPixels) {
    CameraView view = cameraViewFromPrim(handCamera(), 200);
    ASSERT_EQ(view.imageWidth, 200);
    ASSERT_EQ(view.imageHeight, 100);  // 200 * 20 / 40
    EXPECT_FALSE(view.orthographic);
    // At 10 units the view is 2 * 0.4 * 10 = 8 wide and 4 high.
    expectPixel(view, {0, 0, -10}, 100, 50);
    expectPixel(view, {4, 0, -10}, 200, 50);   // right edge
    expectPixel(view, {0, 2, -10}, 100, 0);    // top edge (pixel rows go down)
    expectPixel(view, {-4, -2, -10}, 0, 100);  // bottom-left corner
    expectPixel(view, {2, 1, -10}, 150, 25);
    expectPixel(view, {4, 2, -20}, 150, 25);   // twice as far, same direction
}

TEST(CameraView, DepthMapsClippingRangeToZeroOne) {
    CameraView view = cameraViewFromPrim(handCamera(), 200);
    EXPECT_DOUBLE_EQ(view.nearClip, 1.0);
    EXPECT_DOUBLE_EQ(view.farClip, 100.0);
    EXPECT_NEAR(view.worldToPixel({0, 0, -1}).z, 0.0, 1e-9);
    EXPECT_NEAR(view.worldToPixel({0, 0, -100}).z, 1.0, 1e-9);
}

TEST(CameraView, ViewIsTheInverseOfTheCameraTransform) {
    CameraPrim camera = handCamera();
    // Camera at (5, 0, 0), turned 90 degrees about +Y: it looks down world -X.
    camera.worldTransform = glm::translate(glm::dmat4(1.0), glm::dvec3(5, 0, 0)) *
                            glm::rotate(glm::dmat4(1.0), glm::radians(90.0), glm::dvec3(0, 1, 0));
    CameraView view = cameraViewFromPrim(camera, 200);
    expectPixel(view, {-5, 0, 0}, 100, 50);
    // The camera's +X (image right) is world -Z after the turn.
    expectPixel(view, {-5, 0, -4}, 200, 50);
    expectPixel(view, {-5, 2, 0}, 100, 0);
}

TEST(CameraView, ImageHeightTruncatesLikeUsdRecord) {
    // Default apertures: 960 * 15.2908 / 20.955 = 700.51; usdrecord
    // truncates to 700 where rounding would give 701.
    EXPECT_EQ(imageHeightFor(960, 20.955f, 15.2908f), 700);
    EXPECT_EQ(imageHeightFor(1000, 20.955f, 15.2908f), 729);  // 729.70
    EXPECT_EQ(imageHeightFor(1920, 20.955f, 15.2908f), 1401);  // 1401.02
    EXPECT_EQ(imageHeightFor(100, 10.0f, 10.0f), 100);
    EXPECT_EQ(imageHeightFor(100, 10.0f, 20.0f), 200);
    // A zero vertical aperture gives aspect 0, which usdrecord replaces by 1.
    EXPECT_EQ(imageHeightFor(100, 10.0f, 0.0f), 100);
    // Never less than one row.
    EXPECT_EQ(imageHeightFor(3, 1000.0f, 1.0f), 1);
    EXPECT_EQ(cameraViewFromPrim(CameraPrim(), 960).imageHeight, 700);
}

TEST(CameraView, WindowIsFittedToTheTruncatedImage) {
    // 960 x 700 is a little wider than the 20.955 x 15.2908 aperture, so
    // the Fit policy keeps the vertical field and widens the horizontal one.
    CameraPrim camera;
    CameraView view = cameraViewFromPrim(camera, 960);
    ASSERT_EQ(view.imageHeight, 700);
    const double hAp = camera.horizontalAperture, vAp = camera.verticalAperture;
    const double tanHalfV = vAp / 100.0;
    const double tanHalfH = hAp / 100.0;
    expectPixel(view, {0, tanHalfV * 10, -10}, 480, 0);
    glm::dvec3 edge = view.worldToPixel({tanHalfH * 10, 0, -10});
    const double imageAspect = 960.0 / 700.0;
    const double apertureAspect = hAp / vAp;
    EXPECT_NEAR(edge.x, 480.0 + 480.0 * apertureAspect / imageAspect, 1e-6);
    EXPECT_LT(edge.x, 959.9);  // the aperture now ends 0.35 pixels inside the border
}

TEST(CameraView, ApertureOffsetShiftsTheImage) {
    CameraPrim camera = handCamera();
    camera.horizontalApertureOffset = 4.0f;  // the window moves right by 4 / 50 per unit depth
    camera.verticalApertureOffset = -2.0f;   // and down by 2 / 50
    CameraView view = cameraViewFromPrim(camera, 200);
    // The window's centre is now the direction (0.08, -0.04, -1).
    expectPixel(view, {0.8, -0.4, -10}, 100, 50);
    // The optical axis moves left of and above the centre: window x range
    // [-0.32, 0.48], y range [-0.24, 0.16].
    expectPixel(view, {0, 0, -10}, 200 * 0.32 / 0.8, 100 * 0.16 / 0.4);
}

TEST(CameraView, OrthographicWidthIsATenthOfTheAperture) {
    CameraPrim camera = handCamera();
    camera.projection = Projection::Orthographic;
    CameraView view = cameraViewFromPrim(camera, 200);
    EXPECT_TRUE(view.orthographic);
    EXPECT_EQ(view.imageHeight, 100);
    // 40 tenths wide = 4 units, 2 units high, at any depth.
    expectPixel(view, {2, 0, -5}, 200, 50);
    expectPixel(view, {1, 0.5, -5}, 150, 25);
    expectPixel(view, {1, 0.5, -50}, 150, 25);
    camera.horizontalApertureOffset = 10.0f;  // one scene unit to the right
    expectPixel(cameraViewFromPrim(camera, 200), {1, 0, -5}, 100, 50);
}

TEST(CameraView, FrameBoundsCentresAndContainsACubeYUp) {
    glm::dvec3 lo(-1, 0, -3), hi(3, 4, 1);
    CameraView view = frameBounds(lo, hi, UpAxis::Y, 960);
    EXPECT_EQ(view.imageWidth, 960);
    EXPECT_EQ(view.imageHeight, 700);
    EXPECT_FALSE(view.orthographic);
    glm::dvec3 centre = view.worldToPixel(0.5 * (lo + hi));
    EXPECT_NEAR(centre.x, 480.0, 1e-6);
    EXPECT_NEAR(centre.y, 350.0, 1e-6);
    for (const glm::dvec3& corner : corners(lo, hi)) EXPECT_TRUE(inside(view, corner));
    // usdrecord's camera: on +Z of the centre at r / tan(hfov/2) + depth/2.
    CameraPrim camera = framingCamera(lo, hi, UpAxis::Y);
    const double distance = std::sqrt(8.0) / (static_cast<double>(20.955f) / 100.0) + 2.0;
    glm::dvec3 position(camera.worldTransform[3]);
    EXPECT_NEAR(position.x, 1.0, 1e-9);
    EXPECT_NEAR(position.y, 2.0, 1e-9);
    EXPECT_NEAR(position.z, -1.0 + distance, 1e-9);
    EXPECT_FLOAT_EQ(camera.focalLength, 50.0f);
}

TEST(CameraView, FrameBoundsZUpLooksAlongPlusYWithZUp) {
    glm::dvec3 lo(-2, -1, 0), hi(2, 1, 3);
    CameraView view = frameBounds(lo, hi, UpAxis::Z, 640);
    glm::dvec3 centre = view.worldToPixel(0.5 * (lo + hi));
    EXPECT_NEAR(centre.x, 320.0, 1e-6);
    EXPECT_NEAR(centre.y, 0.5 * view.imageHeight, 1e-6);
    for (const glm::dvec3& corner : corners(lo, hi)) EXPECT_TRUE(inside(view, corner));
    // +Z is up in the image and +X is to the right.
    EXPECT_LT(view.worldToPixel({0, 0, 3}).y, view.worldToPixel({0, 0, 0}).y);
    EXPECT_GT(view.worldToPixel({2, 0, 1.5}).x, 320.0);
    // The camera sits on -Y of the bounds.
    CameraPrim camera = framingCamera(lo, hi, UpAxis::Z);
    EXPECT_LT(camera.worldTransform[3].y, -1.0);
    EXPECT_NEAR(camera.worldTransform[3].x, 0.0, 1e-9);
    EXPECT_NEAR(camera.worldTransform[3].z, 1.5, 1e-9);
}

TEST(CameraView, UsdRecordFramingCropsTallBoundsFitAllDoesNot) {
    // A tall thin box: usdrecord fits its face's half-diagonal to half the
    // image WIDTH, and the image is only 0.73 times as high, so the top and
    // bottom are cut, as in usdrecord's own images.
    glm::dvec3 lo(-0.5, 0, -0.5), hi(0.5, 10, 0.5);
    CameraView usdrecord = frameBounds(lo, hi, UpAxis::Y, 960);
    EXPECT_FALSE(inside(usdrecord, {0.5, 10, 0.5}));
    for (UpAxis up : {UpAxis::Y, UpAxis::Z}) {
        glm::dvec3 tallHi = up == UpAxis::Y ? hi : glm::dvec3(0.5, 0.5, 10);
        glm::dvec3 tallLo = up == UpAxis::Y ? lo : glm::dvec3(-0.5, -0.5, 0);
        CameraView fit = frameBounds(tallLo, tallHi, up, 960, FramingStyle::FitAll);
        for (const glm::dvec3& corner : corners(tallLo, tallHi)) EXPECT_TRUE(inside(fit, corner));
        glm::dvec3 top = fit.worldToPixel(up == UpAxis::Y ? glm::dvec3(0, 10, 0.5)
                                                         : glm::dvec3(0, -0.5, 10));
        EXPECT_NEAR(top.y, 0.0, 1e-6);  // just fits: the front top edge touches the border
        glm::dvec3 centre = fit.worldToPixel(0.5 * (tallLo + tallHi));
        EXPECT_NEAR(centre.x, 480.0, 1e-6);
        EXPECT_NEAR(centre.y, 350.0, 1e-6);
    }
}

TEST(CameraView, FrameSmallBoundsBacksAwayFromTheNearPlane) {
    // usdrecord adds its default near distance (1) when the camera would be
    // closer than that.
    glm::dvec3 lo(-0.01), hi(0.01);
    CameraPrim camera = framingCamera(lo, hi, UpAxis::Y);
    const double distance = std::sqrt(0.0002) / (static_cast<double>(20.955f) / 100.0) + 0.01 + 1.0;
    EXPECT_NEAR(camera.worldTransform[3].z, distance, 1e-9);
    CameraView view = cameraViewFromPrim(camera, 100);
    for (const glm::dvec3& corner : corners(lo, hi)) EXPECT_TRUE(inside(view, corner));
}

TEST(CameraView, EmptyBoundsFrameTheUnitCube) {
    glm::dvec3 lo(1.0), hi(-1.0);
    CameraView view = frameBounds(lo, hi, UpAxis::Y, 320);
    CameraView unit = frameBounds(glm::dvec3(-0.5), glm::dvec3(0.5), UpAxis::Y, 320);
    EXPECT_EQ(view.view, unit.view);
    EXPECT_EQ(view.projection, unit.projection);
    expectPixel(view, {0, 0, 0}, 160, 0.5 * view.imageHeight);
    EXPECT_GT(view.nearClip, 0.0);
    EXPECT_LT(view.nearClip, view.farClip);
}
