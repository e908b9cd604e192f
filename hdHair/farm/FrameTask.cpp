#include "hdHair/farm/FrameTask.h"

#include <csignal>
#include <cstdio>
#include <cstring>

#include <fmt/format.h>

#include "hdHair/base/AtomicFile.h"
#include "hdHair/farm/ChildProcess.h"
#include "hdHair/farm/CompleteFrame.h"
#include "hdHair/farm/FarmJob.h"
#include "hdHair/farm/FrameRecord.h"

namespace hdhair::farm {

namespace {

constexpr int kMachineFailedStatus = 75;  // hdhair-record's EX_TEMPFAIL
constexpr const char* kErrorPrefix = "hdhair-record: error: ";

}  // namespace

bool isMachineFailure(int status, int signal) { return signal != 0 || status == kMachineFailedStatus; }

FrameTaskResult runFrameTask(const FarmJob& job, int task, const std::string& slurmJobId) {
    FrameTaskResult result;
    for (double frame : job.chunk(task)) {
        FrameRecord record;
        record.frame = frame;
        record.slurmJobId = slurmJobId;
        record.task = task;
        record.log = job.taskLog(task);
        const std::string output = job.outputOf(frame);
        // Another job, or an earlier try of this one, may have finished it
        // since the submission looked.
        if (!job.force && whyFrameIncomplete(output, job.imageWidth, job.imageHeight).empty()) {
            record.state = FrameState::Done;
            writeFrameRecord(job, record);
            std::printf("hdhair-farm: frame %s: complete already, skipped\n", frameName(frame).c_str());
            ++result.skipped;
            continue;
        }
        std::vector<std::string> argv = {job.recordExecutable};
        argv.insert(argv.end(), job.recordArguments.begin(), job.recordArguments.end());
        argv.insert(argv.end(), {"--frames", frameName(frame), "--stats", job.statsFile(frame)});
        // A try killed before it could clean up (SIGKILL, scancel, a node
        // going down) leaves its hidden temporary image and stats behind;
        // this task owns the frame now, so they go before each try and after
        // a killed one.
        const auto removeLeftovers = [&] {
            const int removed = removeLeftoverTemporaries(output) + removeLeftoverTemporaries(job.statsFile(frame));
            if (removed)
                std::printf("hdhair-farm: frame %s: removed %d temporary file(s) a killed try left\n",
                            frameName(frame).c_str(), removed);
        };
        for (;;) {
            removeLeftovers();
            ++record.attempts;
            record.state = FrameState::Running;
            writeFrameRecord(job, record);
            std::printf("hdhair-farm: frame %s: rendering (try %d)\n", frameName(frame).c_str(), record.attempts);
            std::fflush(stdout);
            std::string errorLine;
            const ChildExit exit = runChild(argv, job.workingDirectory, [&](const std::string& line) {
                if (line.rfind(kErrorPrefix, 0) == 0) errorLine = line.substr(std::strlen(kErrorPrefix));
            });
            record.seconds = exit.seconds;
            record.peakMemoryKB = exit.peakMemoryKB;
            if (exit.started && exit.status == 0) {
                record.state = FrameState::Done;
                record.rendered = true;
                record.error.clear();
                break;
            }
            if (exit.signal != 0) removeLeftovers();
            if (!exit.started) record.error = exit.startError;
            else if (exit.signal != 0) record.error = fmt::format("hdhair-record was killed by signal {} ({})",
                                                                  exit.signal, strsignal(exit.signal));
            else record.error = errorLine.empty() ? fmt::format("hdhair-record exited with status {}", exit.status)
                                                  : errorLine;
            const bool retry = exit.started && isMachineFailure(exit.status, exit.signal);
            record.inputError = exit.started && !retry;
            if (!retry || record.attempts > job.retries) {
                record.state = FrameState::Failed;
                break;
            }
            std::fprintf(stderr, "hdhair-farm: frame %s: %s; trying again (%d of %d retries)\n",
                         frameName(frame).c_str(), record.error.c_str(), record.attempts, job.retries);
        }
        writeFrameRecord(job, record);
        if (record.state == FrameState::Done) {
            ++result.rendered;
            std::printf("hdhair-farm: frame %s: rendered in %.2f s\n", frameName(frame).c_str(), record.seconds);
        } else {
            ++result.failed;
            std::fprintf(stderr, "hdhair-farm: frame %s failed: %s\n", frameName(frame).c_str(), record.error.c_str());
        }
        std::fflush(stdout);
    }
    return result;
}

}  // namespace hdhair::farm
