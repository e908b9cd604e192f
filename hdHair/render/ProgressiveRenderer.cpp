#include "hdHair/render/ProgressiveRenderer.h"

#include <chrono>
#include <exception>
#include <utility>

#include "hdHair/base/Diagnostics.h"

namespace hdhair {

namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

const char* toString(FrameQuality quality) { return quality == FrameQuality::Preview ? "preview" : "final"; }

ProgressiveRenderer::ProgressiveRenderer(Renderer& renderer, std::mutex& rendererMutex, Diagnostics& diagnostics)
    : renderer_(renderer), rendererMutex_(rendererMutex), diagnostics_(diagnostics), thread_([this] { loop(); }) {}

ProgressiveRenderer::~ProgressiveRenderer() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = true;
    }
    cancellation_.request();
    wake_.notify_all();
    thread_.join();
}

uint64_t ProgressiveRenderer::submit(FrameRequest request) {
    uint64_t number = 0;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        number = ++submitted_;
        pending_.emplace(number, std::move(request));
        // Raised after the request is in place: the thread clears it only
        // when it takes a request, so the full frame in flight sees it.
        cancellation_.request();
    }
    wake_.notify_all();
    return number;
}

std::optional<FinishedFrame> ProgressiveRenderer::takeFinished() {
    std::lock_guard<std::mutex> lock(mutex_);
    std::optional<FinishedFrame> frame = std::move(finished_);
    finished_.reset();
    return frame;
}

FinishedFrame ProgressiveRenderer::waitForFinished() {
    std::unique_lock<std::mutex> lock(mutex_);
    finishedChanged_.wait(lock, [this] { return finished_.has_value(); });
    FinishedFrame frame = std::move(*finished_);
    finished_.reset();
    return frame;
}

uint64_t ProgressiveRenderer::rendering() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return rendering_;
}

ProgressiveRenderer::Counts ProgressiveRenderer::counts() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return counts_;
}

void ProgressiveRenderer::loop() {
    for (;;) {
        uint64_t number = 0;
        FrameRequest request;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            wake_.wait(lock, [this] { return stopping_ || pending_.has_value(); });
            if (stopping_) return;
            number = pending_->first;
            request = std::move(pending_->second);
            pending_.reset();
            rendering_ = number;
            cancellation_.clear();
        }
        const int budget = request.settings.values().interactiveBudgetMs;
        bool superseded = false;
        const bool slow = lastFinalMilliseconds_ && *lastFinalMilliseconds_ > double(budget);
        if (budget > 0 && (slow || lastFinalStopped_)) {
            renderFrame(number, request, FrameQuality::Preview);
            std::lock_guard<std::mutex> lock(mutex_);
            // The view changed again while the preview rendered: its full
            // frame would be stopped at once; the newer view's preview is
            // what the host wants next.
            superseded = pending_.has_value() || stopping_;
        }
        if (!superseded) lastFinalStopped_ = !renderFrame(number, request, FrameQuality::Final);
        std::lock_guard<std::mutex> lock(mutex_);
        rendering_ = 0;
    }
}

bool ProgressiveRenderer::renderFrame(uint64_t number, const FrameRequest& request, FrameQuality quality) {
    FinishedFrame frame;
    frame.request = number;
    frame.quality = quality;
    const bool preview = quality == FrameQuality::Preview;
    const double budget = double(request.settings.values().interactiveBudgetMs);
    Clock::time_point start;
    try {
        std::lock_guard<std::mutex> lock(rendererMutex_);
        start = Clock::now();
        FrameControl control;
        if (preview) {
            frame.previewDivisor = previewBudget_.pixelDivisor();
            frame.previewCurveStride = previewBudget_.curveStride();
            control.preview = true;
            control.previewCurveStride = frame.previewCurveStride;
            frame.result = renderer_.render(request.scene, previewCamera(request.camera, frame.previewDivisor),
                                            previewSettings(request.settings), diagnostics_,
                                            RenderOutputs{request.ids}, control);
            enlargePreview(frame.result, request.camera.imageWidth, request.camera.imageHeight);
        } else {
            control.cancellation = &cancellation_;
            frame.result =
                renderer_.render(request.scene, request.camera, request.settings, diagnostics_,
                                 RenderOutputs{request.ids}, control);
        }
    } catch (const FrameCancelled&) {
        std::lock_guard<std::mutex> lock(mutex_);
        ++counts_.cancelled;
        return false;
    } catch (const std::exception& error) {
        if (preview) {
            // The full frame comes next and reports its own failure, if it
            // fails too; a preview alone failing is only worth a warning.
            diagnostics_.warn("render", std::string("the preview could not be rendered: ") + error.what());
            return true;
        }
        frame.result = RenderResult{};
        frame.error = error.what();
    }
    frame.milliseconds = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    if (preview) {
        previewBudget_.recordPreview(frame.milliseconds, budget);
    } else if (frame.error.empty()) {
        lastFinalMilliseconds_ = frame.milliseconds;
        previewBudget_.recordFullFrame(frame.milliseconds, budget);
    }
    publish(std::move(frame));
    return true;
}

void ProgressiveRenderer::publish(FinishedFrame frame) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        ++(frame.quality == FrameQuality::Preview ? counts_.previews : counts_.finals);
        finished_ = std::move(frame);
    }
    finishedChanged_.notify_all();
}

}  // namespace hdhair
