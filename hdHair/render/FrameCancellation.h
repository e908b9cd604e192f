#pragma once
// Stopping a frame in flight. An interactive host that moves the camera
// does not want the rest of the frame it asked for before: the frame is
// asked, between its passes and between the pieces of its strand draws
// (FramePasses.h), whether it should stop, and a frame told to stop ends by
// throwing FrameCancelled with nothing delivered. The renderer's caches stay
// true to what the GPU holds: the uploads still run (the renderer has
// already counted their data as sent), and a shadow map whose passes did
// not all run is forgotten, so the next frame builds it again.

#include <atomic>
#include <stdexcept>

namespace hdhair {

// What a frame polls. An interface so that a test can stop a frame at an
// exact point (the k-th time it is asked); hosts use CancellationFlag.
class FrameCancellation {
public:
    virtual ~FrameCancellation() = default;
    // Asked from the GL thread; true once the frame should stop.
    virtual bool requested() const = 0;
};

// A flag another thread raises.
class CancellationFlag final : public FrameCancellation {
public:
    void request() { requested_.store(true); }
    void clear() { requested_.store(false); }
    bool requested() const override { return requested_.load(); }

private:
    std::atomic<bool> requested_{false};
};

// Thrown by Renderer::render for a frame that stopped on request.
class FrameCancelled : public std::runtime_error {
public:
    FrameCancelled() : std::runtime_error("the frame was cancelled") {}
};

}  // namespace hdhair
