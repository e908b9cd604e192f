// ProgressiveRenderer: frames on a thread of their own. A preview comes
// before a full frame only once full frames are known to be slower than the
// budget, and the full frame that follows it is the synchronous renderer's
// image to the bit; a newer view stops the full frame in flight and replaces
// views not yet started, and the view after a stopped full frame is
// previewed; a view that cannot be rendered is finished with its reason.

#include <cmath>
#include <limits>
#include <mutex>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "HairTuft.h"
#include "SynchronousReference.h"
#include "hdHair/base/Diagnostics.h"
#include "hdHair/render/ProgressiveRenderer.h"

using namespace hdhair;
using namespace hdhair::testscenes;

namespace {

void expectIdentical(const RenderResult& actual, const RenderResult& expected, const std::string& what) {
    EXPECT_EQ(actual.color.pixels, expected.color.pixels) << what;
    EXPECT_EQ(actual.depth.pixels, expected.depth.pixels) << what;
    EXPECT_EQ(actual.primIds, expected.primIds) << what;
    EXPECT_EQ(actual.elementIds, expected.elementIds) << what;
}

RenderSettings withBudget(int milliseconds) {
    RenderSettings settings;
    settings.set("interactiveBudgetMs", std::to_string(milliseconds));
    return settings;
}

FrameRequest requestFor(const Scene& scene, const CameraView& camera, const RenderSettings& settings) {
    return FrameRequest{scene, camera, settings, true};
}

// Takes finished frames until the full frame of `request`.
FinishedFrame waitForFinal(ProgressiveRenderer& progressive, uint64_t request) {
    for (;;) {
        FinishedFrame frame = progressive.waitForFinished();
        if (frame.request == request && frame.quality == FrameQuality::Final) return frame;
    }
}

}  // namespace

TEST(ProgressiveRenderer, APreviewPrecedesASlowFullFrameWhichIsTheSynchronousImage) {
    const Scene scene = hairTuft(30);
    // A turn of the camera: the full frame keeps the first view's shadow
    // maps, which a preview must leave alone (it draws none).
    const CameraView first = tuftCamera(0.0, 192), second = tuftCamera(5.0, 192);
    // Every full frame takes longer than 1 ms (a GL frame with a readback),
    // so once one is in, every new view gets a preview first.
    const RenderSettings settings = withBudget(1);
    Diagnostics diagnostics;
    const RenderResult expected = synchronousSecondFrame(scene, first, scene, second, settings, diagnostics);

    Renderer renderer(gl::defaultGlBackend());
    std::mutex rendererMutex;
    ProgressiveRenderer progressive(renderer, rendererMutex, diagnostics);
    // The first view: how long a frame takes is not known yet, so no preview.
    const FinishedFrame firstFrame = waitForFinal(progressive, progressive.submit(requestFor(scene, first, settings)));
    EXPECT_TRUE(firstFrame.error.empty()) << firstFrame.error;
    EXPECT_EQ(progressive.counts().previews, 0u);
    EXPECT_GT(firstFrame.milliseconds, 1.0);

    const uint64_t request = progressive.submit(requestFor(scene, second, settings));
    // The preview comes first (the newest frame is taken, so a host polling
    // less often than frames finish may see only the full frame).
    const FinishedFrame earliest = progressive.waitForFinished();
    EXPECT_EQ(earliest.request, request);
    const FinishedFrame final =
        earliest.quality == FrameQuality::Final ? earliest : waitForFinal(progressive, request);
    EXPECT_EQ(progressive.counts().previews, 1u);
    EXPECT_EQ(progressive.counts().finals, 2u);
    EXPECT_EQ(progressive.counts().cancelled, 0u);
    if (earliest.quality == FrameQuality::Preview) {
        // A whole image at the host's size, drawn without shadows.
        EXPECT_EQ(earliest.result.color.width, 192);
        EXPECT_EQ(earliest.result.color.height, second.imageHeight);
        EXPECT_EQ(earliest.result.primIds.size(), size_t(192 * second.imageHeight));
        EXPECT_EQ(earliest.result.stats.shadowMapsRebuilt + earliest.result.stats.shadowMapsKept, 0u);
        EXPECT_NE(earliest.result.color.pixels, expected.color.pixels);
    }
    // The preview changed nothing the full frame relies on: the full frame
    // keeps the maps the first view built, as the synchronous renderer's
    // does, and is its image to the bit.
    EXPECT_EQ(expected.stats.shadowMapsKept, 2u);
    EXPECT_EQ(final.result.stats.shadowMapsKept, 2u);
    EXPECT_EQ(final.result.stats.shadowMapsRebuilt, 0u);
    expectIdentical(final.result, expected, "the full frame after a preview");
    EXPECT_TRUE(diagnostics.warnings().empty());
}

TEST(ProgressiveRenderer, NoPreviewsWithABudgetOfZero) {
    const Scene scene = hairTuft(10);
    Diagnostics diagnostics;
    Renderer renderer(gl::defaultGlBackend());
    std::mutex rendererMutex;
    ProgressiveRenderer progressive(renderer, rendererMutex, diagnostics);
    for (double degrees : {0.0, 15.0, 30.0}) {
        const uint64_t request = progressive.submit(requestFor(scene, tuftCamera(degrees, 64), withBudget(0)));
        const FinishedFrame frame = progressive.waitForFinished();
        EXPECT_EQ(frame.request, request);
        EXPECT_EQ(frame.quality, FrameQuality::Final);
    }
    EXPECT_EQ(progressive.counts().previews, 0u);
}

TEST(ProgressiveRenderer, ANewViewStopsTheFullFrameInFlightAndReplacesViewsNotStarted) {
    const Scene scene = hairTuft(30);
    const RenderSettings settings = withBudget(0);
    Diagnostics diagnostics;
    RenderResult expected;
    {
        Renderer synchronous(gl::defaultGlBackend());
        expected = synchronous.render(scene, tuftCamera(60.0, 96), settings, diagnostics, RenderOutputs{true});
    }

    Renderer renderer(gl::defaultGlBackend());
    std::mutex rendererMutex;
    ProgressiveRenderer progressive(renderer, rendererMutex, diagnostics);
    uint64_t stopped = 0, replaced = 0, newest = 0;
    {
        // Holding the renderer keeps the thread waiting inside the first
        // view's full frame: it has taken the view and started the frame.
        std::unique_lock<std::mutex> holdRenderer(rendererMutex);
        stopped = progressive.submit(requestFor(scene, tuftCamera(0.0, 96), settings));
        while (progressive.rendering() != stopped) std::this_thread::yield();
        replaced = progressive.submit(requestFor(scene, tuftCamera(30.0, 96), settings));
        newest = progressive.submit(requestFor(scene, tuftCamera(60.0, 96), settings));
    }
    const FinishedFrame frame = progressive.waitForFinished();
    EXPECT_EQ(frame.request, newest);
    EXPECT_EQ(frame.quality, FrameQuality::Final);
    EXPECT_NE(replaced, newest);
    const ProgressiveRenderer::Counts counts = progressive.counts();
    EXPECT_EQ(counts.cancelled, 1u);  // the first view's full frame
    EXPECT_EQ(counts.finals, 1u);     // the newest view's only: the second never started
    EXPECT_EQ(counts.previews, 0u);
    expectIdentical(frame.result, expected, "the newest view");
    EXPECT_TRUE(diagnostics.warnings().empty());
}

// A view that changes faster than full frames finish: each full frame is
// stopped by the next view, so without previews the host would see nothing
// until the view stops, even where a full frame takes a little under the
// budget (on the wavy strands the drag showed 12 images in 95 moves, with
// waits of 2.5 s). After a stopped full frame the next view is previewed
// first, whatever the budget; once a full frame finishes under the budget,
// previews stop again.
TEST(ProgressiveRenderer, AViewAfterAStoppedFullFrameIsPreviewedFirst) {
    const Scene scene = hairTuft(30);
    const RenderSettings settings = withBudget(60000);  // every full frame is under it
    Diagnostics diagnostics;
    Renderer renderer(gl::defaultGlBackend());
    std::mutex rendererMutex;
    ProgressiveRenderer progressive(renderer, rendererMutex, diagnostics);
    uint64_t moved = 0;
    {
        std::unique_lock<std::mutex> holdRenderer(rendererMutex);
        const uint64_t first = progressive.submit(requestFor(scene, tuftCamera(0.0, 64), settings));
        while (progressive.rendering() != first) std::this_thread::yield();
        moved = progressive.submit(requestFor(scene, tuftCamera(20.0, 64), settings));
    }
    const FinishedFrame earliest = progressive.waitForFinished();
    EXPECT_EQ(earliest.request, moved);
    if (earliest.quality == FrameQuality::Preview) waitForFinal(progressive, moved);
    EXPECT_EQ(progressive.counts().cancelled, 1u);
    EXPECT_EQ(progressive.counts().previews, 1u) << "the view after a stopped full frame is previewed";
    EXPECT_EQ(progressive.counts().finals, 1u);

    // That full frame finished under the budget: the next view has none.
    const uint64_t still = progressive.submit(requestFor(scene, tuftCamera(40.0, 64), settings));
    const FinishedFrame next = progressive.waitForFinished();
    EXPECT_EQ(next.request, still);
    EXPECT_EQ(next.quality, FrameQuality::Final);
    EXPECT_EQ(progressive.counts().previews, 1u);
    EXPECT_TRUE(diagnostics.warnings().empty());
}

TEST(ProgressiveRenderer, AViewThatCannotBeRenderedFinishesWithItsReason) {
    const Scene scene = hairTuft(5);
    CameraView broken = tuftCamera(0.0, 32);
    broken.view[3][0] = std::numeric_limits<double>::quiet_NaN();
    Diagnostics diagnostics;
    Renderer renderer(gl::defaultGlBackend());
    std::mutex rendererMutex;
    ProgressiveRenderer progressive(renderer, rendererMutex, diagnostics);
    const uint64_t request = progressive.submit(requestFor(scene, broken, withBudget(0)));
    const FinishedFrame frame = progressive.waitForFinished();
    EXPECT_EQ(frame.request, request);
    EXPECT_EQ(frame.quality, FrameQuality::Final);
    EXPECT_NE(frame.error.find("not finite"), std::string::npos) << frame.error;
    EXPECT_TRUE(frame.result.color.pixels.empty());
    // The thread goes on with the next view.
    const uint64_t next = progressive.submit(requestFor(scene, tuftCamera(0.0, 32), withBudget(0)));
    const FinishedFrame good = progressive.waitForFinished();
    EXPECT_EQ(good.request, next);
    EXPECT_TRUE(good.error.empty()) << good.error;
}
