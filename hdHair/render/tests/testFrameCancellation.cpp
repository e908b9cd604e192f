// Stopping a frame in flight (FrameCancellation.h, FrameControl): a frame
// drawn in pieces gives the single draw's image to the bit on every
// transparency path, a frame stopped at any point throws FrameCancelled,
// and the renderer then renders exactly what a renderer that never saw the
// stopped frame renders (uploads kept, half-built shadow maps built again).

#include <climits>
#include <string>

#include <gtest/gtest.h>

#include "HairTuft.h"
#include "SynchronousReference.h"
#include "hdHair/base/Diagnostics.h"
#include "hdHair/render/FrameCancellation.h"
#include "hdHair/render/Renderer.h"

using namespace hdhair;
using namespace hdhair::testscenes;

namespace {

// Asks the frame to stop the `stopAt`-th time it is asked (1: before its
// first pass); counts how often it was asked.
class StopAtPoll final : public FrameCancellation {
public:
    explicit StopAtPoll(int stopAt) : stopAt_(stopAt) {}
    bool requested() const override { return ++polls_ >= stopAt_; }
    int polls() const { return polls_; }

private:
    int stopAt_;
    mutable int polls_ = 0;
};

void expectIdentical(const RenderResult& actual, const RenderResult& expected, const std::string& what) {
    EXPECT_EQ(actual.color.pixels, expected.color.pixels) << what;
    EXPECT_EQ(actual.depth.pixels, expected.depth.pixels) << what;
    EXPECT_EQ(actual.primIds, expected.primIds) << what;
    EXPECT_EQ(actual.instanceIds, expected.instanceIds) << what;
    EXPECT_EQ(actual.elementIds, expected.elementIds) << what;
}

// `path`: a transparency path drawn by the hardware rasteriser, "compute"
// (the compute rasteriser), or "compute+hardware" (strandRaster=auto on
// tuftWithAWidePrim: the hardware lists the wide prim into the compute
// rasteriser's lists).
RenderSettings tuftSettings(const std::string& path) {
    RenderSettings settings;
    if (path == "compute") {
        settings.set("strandRaster", "compute");
    } else if (path == "compute+hardware") {
        settings.set("strandRaster", "auto");
    } else {
        settings.set("transparency", path);
        settings.set("strandRaster", "hardware");
    }
    settings.set("lightsPerPass", "2");  // three light batches, each drawing the strands again
    return settings;
}

// The scene with /tuft/c's strands 25 times as wide (several pixels in
// tuftCamera at 64 px and more, the others under one), for the
// "compute+hardware" path.
Scene tuftWithAWidePrim(const Scene& tuft) {
    Scene scene = tuft;
    CurvesPrim wide = *scene.curves().at("/tuft/c").prim;
    wide.primvars["widths"].values = {0.5f};
    scene.setCurves(wide);
    return scene;
}

Scene sceneFor(const std::string& path, const Scene& tuft) {
    return path == "compute+hardware" ? tuftWithAWidePrim(tuft) : tuft;
}

}  // namespace

TEST(FrameCancellation, StrandPiecesGiveTheSingleDrawsImageOnEveryPath) {
    const CameraView camera = tuftCamera(0.0, 96);
    Renderer renderer(gl::defaultGlBackend());
    Diagnostics diagnostics;
    for (const char* path : {"binSorted", "unsorted", "opaque", "exact", "compute", "compute+hardware"}) {
        const Scene scene = sceneFor(path, hairTuft(40));
        const RenderSettings settings = tuftSettings(path);
        const RenderResult whole = renderer.render(scene, camera, settings, diagnostics, RenderOutputs{true});
        if (std::string(path).find("compute") == 0) {
            EXPECT_EQ(whole.stats.strandRaster, path);
        }
        StopAtPoll never(INT_MAX);
        FrameControl pieces;
        pieces.cancellation = &never;
        pieces.strandPieceSegments = 7;
        const RenderResult pieced = renderer.render(scene, camera, settings, diagnostics, RenderOutputs{true}, pieces);
        // Asked before every piece of every strand draw (three light batches,
        // and the ids pass where it runs), or after every piece of the
        // fragment lists (exact transparency, the compute rasteriser).
        ASSERT_EQ(whole.stats.segments, 360u);  // 120 curves of 3 spans
        EXPECT_GE(never.polls(), 3 * (360 + 6) / 7) << path;
        expectIdentical(pieced, whole, path);
    }
    EXPECT_TRUE(diagnostics.warnings().empty());
}

TEST(FrameCancellation, AFrameStoppedAtAnyPointLeavesTheRendererAsIfItNeverRan) {
    // The stopped frame changes the hair (one prim moves: its upload and
    // every shadow map are in that frame) and turns the camera.
    const CameraView a = tuftCamera(0.0, 64), b = tuftCamera(35.0, 64);
    auto stoppable = [](const FrameCancellation& cancellation) {
        FrameControl control;
        control.cancellation = &cancellation;
        control.strandPieceSegments = 64;
        return control;
    };
    for (const char* path : {"binSorted", "exact", "compute", "compute+hardware"}) {
        const Scene before = sceneFor(path, hairTuft(30));
        Scene after = before;
        after.setCurves(tuftStrands("/tuft/b", 2, 30, 1.5f));
        const RenderSettings settings = tuftSettings(path);
        Diagnostics diagnostics;
        const RenderResult expected = synchronousSecondFrame(before, a, after, b, settings, diagnostics);
        if (std::string(path).find("compute") == 0) {
            EXPECT_EQ(expected.stats.strandRaster, path);
        }

        Renderer renderer(gl::defaultGlBackend());
        renderer.render(before, a, settings, diagnostics, RenderOutputs{true});
        StopAtPoll never(INT_MAX);
        expectIdentical(renderer.render(after, b, settings, diagnostics, RenderOutputs{true}, stoppable(never)),
                        expected, std::string(path) + ", not stopped");
        const int polls = never.polls();
        // Every pass, and every piece of 64 of the 270 segments in three
        // batches (and ids for binSorted), drawn or listed.
        ASSERT_GT(polls, 20) << path;

        for (int stopAt = 1; stopAt <= polls; ++stopAt) {
            renderer.render(before, a, settings, diagnostics, RenderOutputs{true});
            StopAtPoll stop(stopAt);
            EXPECT_THROW(renderer.render(after, b, settings, diagnostics, RenderOutputs{true}, stoppable(stop)),
                         FrameCancelled)
                << path << ", stopped at poll " << stopAt;
            expectIdentical(renderer.render(after, b, settings, diagnostics, RenderOutputs{true}), expected,
                            std::string(path) + ", the frame after one stopped at poll " + std::to_string(stopAt));
        }
        EXPECT_TRUE(diagnostics.warnings().empty()) << path;
    }
}
