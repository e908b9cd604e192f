// SupersampleResolve on images made by hand: colour is the box filter, depth
// and ids come from each pixel's nearest sample, whichever of its samples
// that is.

#include <stdexcept>

#include <gtest/gtest.h>

#include "hdHair/render/Renderer.h"
#include "hdHair/render/SupersampleResolve.h"

using namespace hdhair;

namespace {

// An empty frame with ids: transparent, depth 1, ids -1.
RenderResult emptyFrame(int width, int height) {
    RenderResult frame;
    frame.color = Image(width, height, 4);
    frame.depth = Image(width, height, 1, 1.0f);
    frame.primIds.assign(size_t(width * height), -1);
    frame.instanceIds = frame.elementIds = frame.primIds;
    return frame;
}

// A 4x2 sample frame (two pixels of 2x2 samples) with ids.
RenderResult sampleFrame() {
    RenderResult frame = emptyFrame(4, 2);
    // Left pixel: one covered sample, the last one (not the first, so a
    // resolve that took the first sample, or the centre-nearest upper-left
    // one, would be caught).
    frame.color.at(1, 1, 0) = 0.8f;
    frame.color.at(1, 1, 3) = 1.0f;
    frame.depth.at(1, 1, 0) = 0.4f;
    frame.primIds[5] = 7;
    frame.instanceIds[5] = 2;
    frame.elementIds[5] = 11;
    // Right pixel: two covered samples; the nearer (0.3) names prim 9.
    frame.depth.at(2, 0, 0) = 0.6f;
    frame.primIds[2] = 4;
    frame.depth.at(3, 1, 0) = 0.3f;
    frame.primIds[7] = 9;
    frame.color.at(3, 1, 3) = 0.5f;
    return frame;
}

}  // namespace

TEST(SupersampleResolve, ColourIsTheBoxFilterDepthAndIdsTheNearestSample) {
    RenderResult frame = sampleFrame();
    resolveSupersampling(frame, 2);
    ASSERT_EQ(frame.color.width, 2);
    ASSERT_EQ(frame.color.height, 1);
    EXPECT_FLOAT_EQ(frame.color.at(0, 0, 0), 0.2f);
    EXPECT_FLOAT_EQ(frame.color.at(0, 0, 3), 0.25f);
    EXPECT_FLOAT_EQ(frame.color.at(1, 0, 3), 0.125f);
    ASSERT_EQ(frame.depth.width, 2);
    EXPECT_FLOAT_EQ(frame.depth.at(0, 0, 0), 0.4f);
    EXPECT_FLOAT_EQ(frame.depth.at(1, 0, 0), 0.3f);
    EXPECT_EQ(frame.primIds, (std::vector<int32_t>{7, 9}));
    EXPECT_EQ(frame.instanceIds, (std::vector<int32_t>{2, -1}));
    EXPECT_EQ(frame.elementIds, (std::vector<int32_t>{11, -1}));
}

TEST(SupersampleResolve, EmptyPixelsStayEmptyAndFactorOneChangesNothing) {
    RenderResult frame = sampleFrame();
    const RenderResult same = frame;
    resolveSupersampling(frame, 1);
    EXPECT_EQ(frame.color.pixels, same.color.pixels);
    EXPECT_EQ(frame.primIds, same.primIds);
    RenderResult empty = emptyFrame(4, 4);
    resolveSupersampling(empty, 2);
    EXPECT_EQ(empty.depth.pixels, std::vector<float>(4, 1.0f));
    EXPECT_EQ(empty.primIds, std::vector<int32_t>(4, -1));
}

TEST(SupersampleResolve, NeedsDepthForIdsAndACameraGLCanHold) {
    RenderResult frame = sampleFrame();
    frame.depth = Image();
    EXPECT_THROW(resolveSupersampling(frame, 2), std::logic_error);
    frame.primIds.clear();
    frame.instanceIds.clear();
    frame.elementIds.clear();
    resolveSupersampling(frame, 2);
    EXPECT_EQ(frame.color.width, 2);
    EXPECT_TRUE(frame.depth.pixels.empty());

    CameraView camera;
    camera.imageWidth = 300;
    camera.imageHeight = 200;
    const CameraView fine = supersampledCamera(camera, 3);
    EXPECT_EQ(fine.imageWidth, 900);
    EXPECT_EQ(fine.imageHeight, 600);
    EXPECT_EQ(fine.projection, camera.projection);
    camera.imageWidth = 2049;
    EXPECT_THROW(supersampledCamera(camera, 8), std::invalid_argument);
    EXPECT_THROW(supersampledCamera(camera, 0), std::invalid_argument);
}
