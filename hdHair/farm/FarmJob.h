#pragma once
// A farm job: one frame range of one hdhair-record command, cut into chunks,
// one chunk per Slurm array task. It lives in the job folder as job.json,
// written by `hdhair-farm submit` and read by every task and by
// `hdhair-farm status`, so the folder must be on storage the nodes share
// (as the outputs are). docs/farm.md describes the folder.

#include <string>
#include <vector>

namespace hdhair::farm {

struct FarmJob {
    std::string jobFolder;                 // absolute
    std::string recordExecutable;          // absolute path of hdhair-record
    std::vector<std::string> recordArguments;  // hdhair-record's own, without --frames
    std::string outputPattern;             // the '#' pattern, as hdhair-record expands it
    std::string workingDirectory;          // where relative paths in the arguments resolve
    std::vector<double> allFrames;         // every frame of --frames
    std::vector<double> framesToRender;    // those not complete at submission (all with --force)
    int chunkSize = 1;
    int imageWidth = 0, imageHeight = 0;   // a complete frame's image size (hdhair-record --check)
    int retries = 1;                       // further tries of a frame the machine failed
    bool force = false;                    // render complete frames again
    std::vector<std::string> slurmJobIds;  // every submission of this folder, the latest last

    int taskCount() const;
    // The frames array task `task` renders (0-based, as SLURM_ARRAY_TASK_ID).
    std::vector<double> chunk(int task) const;
    // The array task that renders `frame` in the latest submission, or -1.
    int taskOf(double frame) const;
    std::string outputOf(double frame) const;
    std::string latestJobId() const { return slurmJobIds.empty() ? std::string() : slurmJobIds.back(); }

    std::string jobFile() const { return jobFolder + "/job.json"; }
    std::string taskLog(int task) const;  // Slurm's --output for the task
    std::string statsFile(double frame) const;
    std::string recordFile(double frame) const;

    void save() const;                     // atomically
    static FarmJob load(const std::string& jobFolder);  // throws std::runtime_error, one line
};

// The folder a job keeps beside its outputs when none is given:
// "renders/bear.####.exr" -> "renders/bear.farm".
std::string defaultJobFolder(const std::string& outputPattern);

// A frame as file names and messages show it: 7, 7.5.
std::string frameName(double frame);

}  // namespace hdhair::farm
