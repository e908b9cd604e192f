#include "hdHair/gl/PassTimer.h"

#include <string>

namespace hdhair::gl {

const char* toString(PassTiming timing) {
    switch (timing) {
    case PassTiming::Off: return "off";
    case PassTiming::CpuSynchronised: return "cpu (glFinish after each pass)";
    case PassTiming::GpuQueries: return "gpu (timer queries)";
    }
    return "off";
}

PassTiming passTimingFor(const std::string& glRenderer) {
    return glRenderer.find("llvmpipe") != std::string::npos ? PassTiming::CpuSynchronised : PassTiming::GpuQueries;
}

PassTimer::PassTimer(PassTiming timing, size_t passes)
    : timing_(timing), used_(passes, false), onCpu_(passes, false), milliseconds_(passes, 0.0) {
    if (timing_ == PassTiming::GpuQueries && passes > 0) {
        queries_.resize(passes);
        glCreateQueries(GL_TIME_ELAPSED, GLsizei(passes), queries_.data());
    }
}

PassTimer::~PassTimer() {
    if (!queries_.empty()) glDeleteQueries(GLsizei(queries_.size()), queries_.data());
}

void PassTimer::begin(size_t pass, bool cpuWork) {
    if (timing_ == PassTiming::Off) return;
    used_[pass] = true;
    onCpu_[pass] = cpuWork || timing_ == PassTiming::CpuSynchronised;
    if (!onCpu_[pass]) glBeginQuery(GL_TIME_ELAPSED, queries_[pass]);
    start_ = Clock::now();
}

void PassTimer::end(size_t pass) {
    if (!used_[pass]) return;
    if (!onCpu_[pass]) {
        glEndQuery(GL_TIME_ELAPSED);
        return;
    }
    if (timing_ == PassTiming::CpuSynchronised) glFinish();
    milliseconds_[pass] = std::chrono::duration<double, std::milli>(Clock::now() - start_).count();
}

std::vector<double> PassTimer::collect() {
    if (timing_ == PassTiming::GpuQueries) {
        for (size_t pass = 0; pass < queries_.size(); ++pass) {
            if (!used_[pass] || onCpu_[pass]) continue;
            GLuint64 nanoseconds = 0;
            glGetQueryObjectui64v(queries_[pass], GL_QUERY_RESULT, &nanoseconds);
            milliseconds_[pass] = double(nanoseconds) * 1e-6;
        }
    }
    return milliseconds_;
}

}  // namespace hdhair::gl
