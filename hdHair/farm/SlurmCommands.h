#pragma once
// Slurm, through its own commands (sbatch, squeue): hdhair-farm schedules
// nothing itself. The commands read $SLURM_CONF like any Slurm client.

#include <optional>
#include <string>
#include <vector>

namespace hdhair::farm {

// One array job of `tasks` tasks, each running `taskCommand` (a shell line).
struct ArrayJobRequest {
    std::string jobName;
    int tasks = 1;
    int tasksAtOnce = 0;                  // 0: as many as Slurm fits
    std::string logPattern;               // --output, with %a for the task
    std::string workingDirectory;         // --chdir
    std::string taskCommand;              // --wrap
    std::string partition, account, timeLimit, memory;  // passed through when set
    int cpusPerTask = 0;                  // 0: Slurm's default
    std::vector<std::string> extraOptions;  // further sbatch options, as given
};

std::vector<std::string> sbatchArguments(const ArrayJobRequest& request);

// Submits it; returns the job id. Throws std::runtime_error with sbatch's own
// error line (an unreachable controller, a partition that does not exist).
std::string submitArrayJob(const ArrayJobRequest& request);

struct QueuedTask {
    int task = -1;        // the array index
    std::string state;    // PENDING, RUNNING, COMPLETING, ...
};

// The job's tasks Slurm still holds (pending, running, completing); empty
// once the job has ended. None, with `error` set, when squeue fails.
std::optional<std::vector<QueuedTask>> queuedTasks(const std::string& jobId, std::string& error);

// squeue -h -r -o '%i|%T' lines, e.g. "41_3|RUNNING", for job `jobId`.
std::vector<QueuedTask> parseQueuedTasks(const std::string& squeueOutput, const std::string& jobId);

// A word for a shell line, in single quotes.
std::string shellQuoted(const std::string& word);

}  // namespace hdhair::farm
