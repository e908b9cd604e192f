#pragma once
// Renders frames on a thread of its own for interactive hosts (the Hydra
// render pass), as hdEmbree renders on an HdRenderThread: the host submits
// the frame it wants and returns at once, and takes whatever image is
// finished when it next looks. Each image it hands over is complete (a
// preview or a full frame, never part of one).
//
// For each request, in order:
//  1. a preview (InteractivePreview.h), when the last full frame took longer
//     than the request's interactiveBudgetMs (0: never), or was stopped by a
//     newer view: a view that changes faster than full frames finish would
//     otherwise show nothing until it stops, even with full frames a little
//     under the budget. The first frame has none: until one full frame is
//     in (or stopped), how long frames take is unknown.
//     Previews are not cancelled: they are made to fit the budget, and a view
//     that keeps changing is shown by them, one after another;
//  2. the full frame, unless a newer request came in meanwhile. A request
//     that comes in while it renders stops it (FrameCancellation.h) within a
//     pass or a piece of the strand draws, and the newer request starts.
// Requests not yet started are replaced by newer ones: only the newest view
// is rendered.
//
// Thread-safety: every public function may be called from any thread. The Renderer is used only by this thread,
// under `rendererMutex` (a Renderer renders one frame at a time; several
// ProgressiveRenderers may share one).

#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "hdHair/plan/CameraView.h"
#include "hdHair/render/FrameCancellation.h"
#include "hdHair/render/InteractivePreview.h"
#include "hdHair/plan/RenderSettings.h"
#include "hdHair/render/Renderer.h"
#include "hdHair/scene/Scene.h"

namespace hdhair {

class Diagnostics;

// One view a host wants rendered.
struct FrameRequest {
    Scene scene;  // a snapshot: the host keeps changing its own
    CameraView camera;
    RenderSettings settings;
    bool ids = false;  // RenderOutputs::ids
};

enum class FrameQuality { Preview, Final };
const char* toString(FrameQuality quality);

struct FinishedFrame {
    uint64_t request = 0;  // the number submit() returned
    FrameQuality quality = FrameQuality::Final;
    // At the request's camera size (a preview's pixels enlarged to it).
    // Empty when the frame failed.
    RenderResult result;
    // Why the request could not be rendered (a final frame with no images);
    // empty on success.
    std::string error;
    double milliseconds = 0.0;  // rendering it, enlarging a preview included
    int previewDivisor = 1;      // a preview's pixels across, 1 / this of the request's
    int previewCurveStride = 1;  // a preview drew every this-many-th curve
};

class ProgressiveRenderer {
public:
    // `renderer`, `rendererMutex` and `diagnostics` must outlive this.
    ProgressiveRenderer(Renderer& renderer, std::mutex& rendererMutex, Diagnostics& diagnostics);
    // Stops the frame in flight and the thread.
    ~ProgressiveRenderer();
    ProgressiveRenderer(const ProgressiveRenderer&) = delete;
    ProgressiveRenderer& operator=(const ProgressiveRenderer&) = delete;

    // Asks for a view: replaces a request not yet started and stops a full
    // frame in flight. Returns the request's number (1, 2, ...).
    uint64_t submit(FrameRequest request);

    // The newest frame finished since the last take, if any; older ones not
    // taken are dropped (a host shows the newest image).
    std::optional<FinishedFrame> takeFinished();
    // The same, waiting for one.
    FinishedFrame waitForFinished();

    // The request this thread has taken and not finished with (its preview
    // or full frame rendering, or waiting for the renderer), or 0.
    uint64_t rendering() const;

    struct Counts {
        uint64_t previews = 0, finals = 0;  // finished (failed finals included)
        uint64_t cancelled = 0;             // full frames stopped by a newer request
    };
    Counts counts() const;

private:
    void loop();
    // Renders one frame of `request` on this thread; false when it was cancelled.
    bool renderFrame(uint64_t number, const FrameRequest& request, FrameQuality quality);
    void publish(FinishedFrame frame);

    Renderer& renderer_;
    std::mutex& rendererMutex_;
    Diagnostics& diagnostics_;

    mutable std::mutex mutex_;
    std::condition_variable wake_, finishedChanged_;
    std::optional<std::pair<uint64_t, FrameRequest>> pending_;
    std::optional<FinishedFrame> finished_;
    uint64_t submitted_ = 0;
    uint64_t rendering_ = 0;
    Counts counts_;
    bool stopping_ = false;
    CancellationFlag cancellation_;  // raised by submit() for the full frame in flight

    // This thread's own: how long the last full frame took, and how small
    // previews have to be to fit the budget.
    std::optional<double> lastFinalMilliseconds_;
    bool lastFinalStopped_ = false;  // the last full frame begun was stopped by a newer view
    PreviewBudget previewBudget_;

    std::thread thread_;  // last: starts after everything above exists
};

}  // namespace hdhair
