#pragma once
// The one thread that owns hdHair's GL context. Every GL call the engine makes
// runs here, posted with run(). Hydra hosts (usdview) keep their own GLX
// context current on their threads; under libglvnd an EGL context cannot be
// made current on such a thread (EGL_BAD_ACCESS), so hdHair never tries.

#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <type_traits>

#include "hdHair/gl/GlContext.h"

namespace hdhair::gl {

class GlRenderThread {
public:
    // Starts the thread and creates the context on it. Throws
    // GlUnavailableError (with what was tried) when there is none.
    explicit GlRenderThread(GlBackend backend);
    ~GlRenderThread();
    GlRenderThread(const GlRenderThread&) = delete;
    GlRenderThread& operator=(const GlRenderThread&) = delete;

    // Runs job on the GL thread and waits for it; its result or exception
    // comes back to the caller. Calling run() from a job deadlocks, so jobs
    // call GL directly instead.
    template <typename Job>
    auto run(Job&& job) -> std::invoke_result_t<Job> {
        using Result = std::invoke_result_t<Job>;
        auto task = std::make_shared<std::packaged_task<Result()>>(std::forward<Job>(job));
        std::future<Result> result = task->get_future();
        post([task] { (*task)(); });
        return result.get();
    }

    GlBackend backend() const { return backend_; }
    const std::string& contextDescription() const { return description_; }
    // GlContext::origin() and softwareRendererWarning() of the context.
    const std::string& contextOrigin() const { return origin_; }
    const std::string& softwareRendererWarning() const { return softwareRendererWarning_; }

private:
    void post(std::function<void()> job);
    void loop(std::promise<void>& started);

    GlBackend backend_;
    std::string description_, origin_, softwareRendererWarning_;
    std::unique_ptr<GlContext> context_;
    std::mutex mutex_;
    std::condition_variable wake_;
    std::deque<std::function<void()>> jobs_;
    bool stopping_ = false;
    std::thread thread_;
};

}  // namespace hdhair::gl
