#pragma once
// What became of one frame, written by the array task that owns it into the
// job folder (frames/<frame>.json, atomically) each time its state changes.
// The records, not Slurm's accounting, say which frames are done: a site
// without slurmdbd has no accounting, and a record names the frame, its
// task, its log and hdhair-record's own error line.

#include <optional>
#include <string>

namespace hdhair::farm {

struct FarmJob;

enum class FrameState {
    Running,   // a task started it; if its job has ended, the task was killed
    Done,      // its image is complete (rendered, or found complete and skipped)
    Failed,    // hdhair-record failed it (after the retries a machine failure gets)
};

const char* toString(FrameState state);

struct FrameRecord {
    double frame = 0.0;
    FrameState state = FrameState::Running;
    std::string slurmJobId;
    int task = -1;
    std::string log;            // the task's log file
    bool rendered = false;      // Done: rendered by this job (false: found complete)
    int attempts = 0;           // hdhair-record runs, retries included
    double seconds = 0.0;       // the last run's wall time
    long peakMemoryKB = 0;      // the last run's peak resident memory
    std::string error;          // Failed: hdhair-record's error line, or how it died
    bool inputError = false;    // Failed: an error in the input, never retried
};

void writeFrameRecord(const FarmJob& job, const FrameRecord& record);
// The frame's record, or none when no task has written one.
std::optional<FrameRecord> readFrameRecord(const FarmJob& job, double frame);

}  // namespace hdhair::farm
