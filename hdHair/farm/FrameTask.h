#pragma once
// One Slurm array task: renders its chunk of the job's frames, one
// hdhair-record process per frame, and records what became of each
// (FrameRecord). A frame per process costs a process start and a stage read
// each (docs/farm.md measures it) and buys what a farm needs: a task killed
// mid-chunk loses only the frame it was on, each frame has its own --stats
// and exit status, and a machine failure is retried for that frame alone.

#include <string>

namespace hdhair::farm {

struct FarmJob;

struct FrameTaskResult {
    int rendered = 0, skipped = 0, failed = 0;
};

// Frames already complete are skipped (unless the job forces them); a frame
// hdhair-record fails with status 75 (the machine: out of memory, no GL) or
// that dies by a signal is tried again up to job.retries times; an input
// error (status 1 or 2) never is.
FrameTaskResult runFrameTask(const FarmJob& job, int task, const std::string& slurmJobId);

// True when hdhair-record's exit (status, or the signal that killed it) says
// the machine, not the input, failed the frame: worth another try.
bool isMachineFailure(int status, int signal);

}  // namespace hdhair::farm
