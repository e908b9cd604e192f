#include "hdHair/gl/GlRenderThread.h"

#include <pthread.h>

namespace hdhair::gl {

GlRenderThread::GlRenderThread(GlBackend backend) : backend_(backend) {
    std::promise<void> started;
    std::future<void> startedFuture = started.get_future();
    thread_ = std::thread([this, &started] { loop(started); });
    try {
        startedFuture.get();
    } catch (...) {
        thread_.join();
        throw;
    }
}

GlRenderThread::~GlRenderThread() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = true;
    }
    wake_.notify_one();
    if (thread_.joinable()) thread_.join();
}

void GlRenderThread::post(std::function<void()> job) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        jobs_.push_back(std::move(job));
    }
    wake_.notify_one();
}

void GlRenderThread::loop(std::promise<void>& started) {
    // Named for profilers (top -H, perf, /proc/PID/task/TID/comm). Threads
    // the driver starts from here inherit the name unless they set their own:
    // llvmpipe's rasteriser threads are llvmpipe-N, its compute workers stay
    // hdhair-gl (scripts/strand-raster-bench.py tells them apart).
    pthread_setname_np(pthread_self(), "hdhair-gl");
    try {
        context_ = createGlContext(backend_);
        description_ = context_->description();
        origin_ = context_->origin();
        softwareRendererWarning_ = context_->softwareRendererWarning();
    } catch (...) {
        started.set_exception(std::current_exception());
        return;
    }
    started.set_value();
    for (;;) {
        std::function<void()> job;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            wake_.wait(lock, [this] { return stopping_ || !jobs_.empty(); });
            if (jobs_.empty()) break;  // stopping, and nothing left to do
            job = std::move(jobs_.front());
            jobs_.pop_front();
        }
        job();  // packaged_task: exceptions are delivered to the caller's future
    }
    // The context is destroyed on the thread it is current on.
    context_.reset();
}

}  // namespace hdhair::gl
