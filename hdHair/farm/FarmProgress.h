#pragma once
// Where a farm job stands, from its frame records and Slurm's queue: the
// progress line `hdhair-farm submit --wait` and `status` print, and the
// report at the end (failures with their task, log and error; the frames to
// resubmit; the frame-time summary).

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hdHair/farm/FrameRecord.h"
#include "hdHair/farm/SlurmCommands.h"

namespace hdhair::farm {

struct FarmJob;

struct FarmProgress {
    int total = 0;           // every frame of --frames
    int done = 0;            // complete: rendered by this job, or complete before it
    int rendered = 0;        // of `done`, rendered by this job's tasks
    int running = 0;
    int failed = 0;
    int waiting = 0;         // not started, the job still queued or running
    bool jobActive = false;  // Slurm still holds some of its tasks
    bool queueKnown = true;  // false when squeue failed (the line says so)
    std::string queueError;
    int tasksRunning = 0, tasksPending = 0;
    double secondsLeft = -1.0;              // -1: not known yet
    std::vector<FrameRecord> failures;      // in frame order
    std::vector<double> notRendered;        // the job ended without them (cancelled, killed)
    std::vector<FrameRecord> renderedRecords;

    bool complete() const { return done == total; }
    // Frames to submit again: the failed ones and those never rendered.
    std::vector<double> framesToResubmit() const;
};

// `queue` is queuedTasks() of the latest job (none: squeue failed).
FarmProgress measureProgress(const FarmJob& job, const std::optional<std::vector<QueuedTask>>& queue,
                             const std::string& queueError = "");

// "hdhair-farm: job 41: 10/24 frames done, 2 running, 0 failed, 12 waiting; about 35 s left"
std::string progressLine(const FarmJob& job, const FarmProgress& progress);

// The end of a job: each failed frame with task, log and error, the frames
// not rendered, the --frames spec to resubmit and the frame-time summary.
std::string finalReport(const FarmJob& job, const FarmProgress& progress);

// frames, total and median frame seconds, peak memory, the slowest frames;
// hdhair-farm writes it to the job folder as summary.json.
nlohmann::json frameTimeSummary(const FarmProgress& progress);

}  // namespace hdhair::farm
