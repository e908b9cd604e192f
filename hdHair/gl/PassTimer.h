#pragma once
// Times the passes of a frame. Two ways, chosen per driver:
//  - GpuQueries: a GL_TIME_ELAPSED query around each pass, read after the
//    frame's readback (which waits for the GPU anyway): no extra stall.
//  - CpuSynchronised: the CPU clock around each pass with glFinish() at its
//    end. Used on Mesa's llvmpipe, whose timer queries cannot time every
//    pass: a query around a pass that draws nothing (the clear) returns
//    nonsense there (hdHair/render/README.md, "Timing passes", has the
//    measurement). Synchronising costs the overlap between
//    passes, so the renderer does it only when the passTimings setting asks.
// Passes that work on the CPU (the bin sort) take the CPU clock either way.
// Off measures nothing.

#include <chrono>
#include <string>
#include <vector>

#include "hdHair/gl/GlObjects.h"

namespace hdhair::gl {

enum class PassTiming { Off, CpuSynchronised, GpuQueries };
const char* toString(PassTiming timing);

// GpuQueries where the driver's timer queries measure whole passes, else
// CpuSynchronised.
PassTiming passTimingFor(const std::string& glRenderer);

class PassTimer {
public:
    PassTimer(PassTiming timing, size_t passes);
    ~PassTimer();
    PassTimer(const PassTimer&) = delete;
    PassTimer& operator=(const PassTimer&) = delete;

    // `cpuWork`: the pass works on the CPU (the bin sort), so the CPU clock
    // measures it whatever the timing (but Off).
    void begin(size_t pass, bool cpuWork = false);
    void end(size_t pass);
    // Milliseconds per pass, after the frame's last GL call; 0 for passes
    // not timed (or with timing off).
    std::vector<double> collect();

private:
    using Clock = std::chrono::steady_clock;
    PassTiming timing_;
    std::vector<GLuint> queries_;
    std::vector<bool> used_, onCpu_;
    std::vector<double> milliseconds_;
    Clock::time_point start_;
};

}  // namespace hdhair::gl
