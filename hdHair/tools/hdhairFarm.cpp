// hdhair-farm: renders a frame range of hdhair-record across a Slurm cluster,
// as one array job whose tasks each render a chunk of frames (docs/farm.md).
//
//   hdhair-farm submit --frames 1:96 [--chunk 4] [--wait] [Slurm options] -- <hdhair-record arguments>
//   hdhair-farm status JOB [--wait]        JOB: a job id, or the job folder
//   hdhair-farm task JOBFOLDER              what each array task runs
//
// Exit status: 0 when every frame is complete (or, without --wait, the job
// was submitted); 1 when a frame failed, frames are missing after the job
// ended, or the submission was refused (one line "hdhair-farm: error: ...",
// nothing submitted); 2 for a command line that does not parse; 3 from
// `status` while the job still runs with nothing failed yet.

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "hdHair/base/AtomicFile.h"
#include "hdHair/farm/ChildProcess.h"
#include "hdHair/farm/CompleteFrame.h"
#include "hdHair/farm/FarmJob.h"
#include "hdHair/farm/FarmProgress.h"
#include "hdHair/farm/FrameTask.h"
#include "hdHair/farm/JobRegistry.h"
#include "hdHair/farm/SlurmCommands.h"
#include "hdHair/base/FrameSpec.h"

namespace {

using namespace hdhair;
using namespace hdhair::farm;
namespace fs = std::filesystem;

constexpr int kStillRunning = 3;

struct SubmitOptions {
    std::string frames, jobFolder, record;
    int chunk = 4, tasksAtOnce = 0, retries = 1, cpusPerTask = 0;
    std::string partition, account, timeLimit, memory;
    std::vector<std::string> sbatchOptions, recordArguments;
    bool force = false, wait = false;
    double pollSeconds = 2.0;
};

// This executable's folder: hdhair-record is installed and built beside it.
fs::path executableFolder() {
    std::error_code error;
    const fs::path self = fs::read_symlink("/proc/self/exe", error);
    if (error) throw std::runtime_error("cannot find this executable (/proc/self/exe): " + error.message());
    return self.parent_path();
}

// hdhair-record's arguments the farm owns: the frames (it chunks them) and
// --stats (each frame gets its own, in the job folder).
void refuseFarmOwnedArguments(const std::vector<std::string>& arguments) {
    for (const std::string& argument : arguments) {
        const std::string name = argument.substr(0, argument.find('='));
        if (name == "--frames" || name == "-f" || name == "--defaultTime" || name == "-d")
            throw std::invalid_argument("give the frames to hdhair-farm (--frames before '--'), not to hdhair-record");
        if (name == "--stats")
            throw std::invalid_argument("hdhair-farm writes each frame's --stats into the job folder (stats/); leave "
                                        "--stats out of hdhair-record's arguments");
        if (name == "--check") throw std::invalid_argument("hdhair-farm runs hdhair-record --check itself");
    }
}

// hdhair-record --check with the farm's frames: what every task would refuse,
// refused here, and the stage, output pattern and image size of the job.
nlohmann::json checkRecordArguments(const std::string& record, const SubmitOptions& options) {
    std::vector<std::string> argv = {record};
    argv.insert(argv.end(), options.recordArguments.begin(), options.recordArguments.end());
    argv.insert(argv.end(), {"--frames", options.frames, "--check"});
    std::string output, errors;
    const ChildExit exit = captureChild(argv, output, errors);
    if (!exit.started) throw std::runtime_error(exit.startError);
    if (exit.status != 0) {
        std::string reason = errors.substr(0, errors.find_last_not_of('\n') + 1);
        reason = reason.substr(reason.rfind('\n') == std::string::npos ? 0 : reason.rfind('\n') + 1);
        const std::string prefix = "hdhair-record: error: ";
        if (reason.rfind(prefix, 0) == 0) reason = reason.substr(prefix.size());
        throw std::invalid_argument("every frame would fail: " +
                                    (reason.empty() ? "hdhair-record --check exited with status " +
                                                          std::to_string(exit.status)
                                                    : reason));
    }
    const nlohmann::json report = nlohmann::json::parse(output, nullptr, false);
    if (report.is_discarded() || !report.contains("imageWidth"))
        throw std::runtime_error("hdhair-record --check printed no report (is '" + record + "' hdhair-record?)");
    for (const nlohmann::json& warning : report.value("warnings", nlohmann::json::array()))
        std::fprintf(stderr, "hdhair-farm: warning: %s\n", warning.get<std::string>().c_str());
    return report;
}

std::string absoluteIn(const std::string& folder, const std::string& path) {
    return (fs::path(folder) / path).lexically_normal().string();
}

// Prints progress until Slurm holds none of the job's tasks, then the
// report; returns the exit status. A line is printed when something changed,
// at most every `pollSeconds`; on a terminal it rewrites itself.
int followJob(const FarmJob& job, double pollSeconds, bool wait) {
    const bool terminal = isatty(STDERR_FILENO);
    std::string lastLine;
    for (;;) {
        std::string queueError;
        const std::optional<std::vector<QueuedTask>> queue = queuedTasks(job.latestJobId(), queueError);
        FarmProgress progress = measureProgress(job, queue, queueError);
        const std::string line = progressLine(job, progress);
        if (line != lastLine) {
            std::fprintf(stderr, terminal ? "\r\033[K%s" : "%s\n", line.c_str());
            lastLine = line;
        }
        if (!progress.jobActive || !wait) {
            if (terminal) std::fprintf(stderr, "\n");
            // A task may write its last record as it leaves the queue.
            if (!progress.jobActive) progress = measureProgress(job, queue, queueError);
            writeTextFileAtomically(job.jobFolder + "/summary.json", frameTimeSummary(progress).dump(2) + "\n");
            if (progress.jobActive) return progress.failed ? 1 : kStillRunning;
            std::fprintf(stderr, "%s", finalReport(job, progress).c_str());
            return progress.complete() ? 0 : 1;
        }
        std::this_thread::sleep_for(std::chrono::duration<double>(pollSeconds));
    }
}

// The submission's checks that need no Slurm: the options, and the
// arguments as hdhair-record --check reads them. Returns what it printed.
nlohmann::json checkedSubmission(const SubmitOptions& options, const std::string& record) {
    if (options.chunk < 1) throw std::invalid_argument("--chunk must be 1 or more frames");
    if (options.retries < 0 || options.retries > 10) throw std::invalid_argument("--retries must be 0 to 10");
    if (options.tasksAtOnce < 0) throw std::invalid_argument("--tasksAtOnce must be 0 (no limit) or more");
    if (options.recordArguments.empty())
        throw std::invalid_argument("no hdhair-record arguments: hdhair-farm submit --frames 1:24 -- stage.usda "
                                    "out.####.exr [options]");
    refuseFarmOwnedArguments(options.recordArguments);
    nlohmann::json check = checkRecordArguments(record, options);
    const std::string pattern = check.at("output").get<std::string>();
    if (!hasFramePlaceholder(pattern))
        throw std::invalid_argument("the output '" + pattern + "' has no '#' for the frame number (e.g. "
                                    "out.####.exr): every task would write the same file");
    return check;
}

// The job as the options and hdhair-record's check describe it, its frames
// not yet chosen.
FarmJob describeJob(const SubmitOptions& options, const std::string& record, const nlohmann::json& check,
                    const std::vector<double>& frames) {
    const std::string pattern = check.at("output").get<std::string>();
    FarmJob job;
    job.workingDirectory = fs::current_path().string();
    job.recordExecutable = fs::absolute(record).lexically_normal().string();
    job.recordArguments = options.recordArguments;
    job.outputPattern = absoluteIn(job.workingDirectory, pattern);
    job.jobFolder = absoluteIn(job.workingDirectory, options.jobFolder.empty() ? defaultJobFolder(pattern)
                                                                               : options.jobFolder);
    job.allFrames = frames;
    job.chunkSize = options.chunk;
    job.imageWidth = check.at("imageWidth").get<int>();
    job.imageHeight = check.at("imageHeight").get<int>();
    job.retries = options.retries;
    job.force = options.force;
    return job;
}

// The job an earlier submission left in the folder, if any; throws while it
// still renders (one job per folder at a time: two would render the same
// frames).
std::optional<FarmJob> previousJob(const FarmJob& job) {
    if (!fs::exists(job.jobFile())) return std::nullopt;
    FarmJob previous = FarmJob::load(job.jobFolder);
    if (previous.latestJobId().empty()) return previous;
    std::string error;
    const auto queue = queuedTasks(previous.latestJobId(), error);
    if (!queue) throw std::runtime_error("cannot ask Slurm about job " + previous.latestJobId() + ": " + error);
    if (!queue->empty())
        throw std::invalid_argument("job " + previous.latestJobId() + " still renders into " + job.jobFolder +
                                    " (hdhair-farm status " + previous.latestJobId() + "); wait for it or scancel it");
    return previous;
}

// Submits the job's array to Slurm; when nothing was submitted, leaves the
// folder as it was before and rethrows.
std::string submitJobArray(const FarmJob& job, const SubmitOptions& options, const std::optional<FarmJob>& previous,
                           bool folderIsNew) {
    ArrayJobRequest request;
    request.jobName = "hdhair-farm:" + fs::path(job.jobFolder).filename().string();
    request.tasks = job.taskCount();
    request.tasksAtOnce = options.tasksAtOnce;
    request.logPattern = job.jobFolder + "/logs/task-%a.log";
    request.workingDirectory = job.workingDirectory;
    request.taskCommand = "exec " + shellQuoted((executableFolder() / "hdhair-farm").string()) + " task " +
                          shellQuoted(job.jobFolder);
    request.partition = options.partition;
    request.account = options.account;
    request.timeLimit = options.timeLimit;
    request.memory = options.memory;
    request.cpusPerTask = options.cpusPerTask;
    request.extraOptions = options.sbatchOptions;
    try {
        return submitArrayJob(request);
    } catch (...) {
        if (previous) previous->save();
        else if (folderIsNew) fs::remove_all(job.jobFolder);
        else fs::remove(job.jobFile());
        throw;
    }
}

int submit(SubmitOptions options) {
    const std::vector<double> frames = parseFrameSpec(options.frames);
    const std::string record =
        options.record.empty() ? (executableFolder() / "hdhair-record").string() : options.record;
    const nlohmann::json check = checkedSubmission(options, record);
    FarmJob job = describeJob(options, record, check, frames);
    const std::optional<FarmJob> previous = previousJob(job);
    if (previous) job.slurmJobIds = previous->slurmJobIds;
    for (double frame : frames)
        if (options.force || !whyFrameIncomplete(job.outputOf(frame), job.imageWidth, job.imageHeight).empty())
            job.framesToRender.push_back(frame);
    const size_t complete = frames.size() - job.framesToRender.size();
    if (job.framesToRender.empty()) {
        std::fprintf(stderr, "hdhair-farm: all %zu frames are complete in %s; nothing to submit (--force renders them "
                             "again)\n",
                     frames.size(), check.at("output").get<std::string>().c_str());
        return 0;
    }

    const bool folderIsNew = !fs::exists(job.jobFolder);
    for (const char* sub : {"frames", "stats", "logs"}) fs::create_directories(job.jobFolder + "/" + sub);
    job.save();
    const std::string jobId = submitJobArray(job, options, previous, folderIsNew);
    job.slurmJobIds.push_back(jobId);
    job.save();
    // The job runs whatever happens here: a registry that cannot be written
    // costs `status JOB` by id only, not the submission's success.
    try {
        registerJob(jobId, job.jobFolder);
    } catch (const std::exception& error) {
        std::fprintf(stderr, "hdhair-farm: warning: job %s is not in the job registry (%s); give its job folder, %s, "
                             "to status\n",
                     jobId.c_str(), error.what(), job.jobFolder.c_str());
    }
    std::fprintf(stderr,
                 "hdhair-farm: submitted job %s: %zu frames in %d tasks of up to %d frames%s; job folder %s\n",
                 jobId.c_str(), job.framesToRender.size(), job.taskCount(), job.chunkSize,
                 complete ? fmt::format(" ({} more complete already, skipped)", complete).c_str() : "",
                 job.jobFolder.c_str());
    if (!options.wait) {
        std::printf("%s\n", jobId.c_str());
        return 0;
    }
    return followJob(job, options.pollSeconds, true);
}

// The chunk and job come from Slurm's array variables unless given (another
// scheduler's task passes its own).
int runTask(const std::string& folder, int task, std::string jobId) {
    if (task < 0) {
        const char* index = std::getenv("SLURM_ARRAY_TASK_ID");
        if (!index) throw std::invalid_argument("hdhair-farm task runs as a Slurm array task (SLURM_ARRAY_TASK_ID is "
                                                "not set; --task gives the chunk elsewhere)");
        task = std::atoi(index);
    }
    if (jobId.empty()) {
        const char* id = std::getenv("SLURM_ARRAY_JOB_ID");
        jobId = id ? id : "";
    }
    const FarmJob job = FarmJob::load(folder);
    const FrameTaskResult result = runFrameTask(job, task, jobId);
    std::printf("hdhair-farm: task %d: %d rendered, %d complete already, %d failed\n", task, result.rendered,
                result.skipped, result.failed);
    return result.failed ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Renders hdhair-record's frames across a Slurm cluster, one array job per frame range "
                 "(docs/farm.md).",
                 "hdhair-farm"};
    app.require_subcommand(1);
    SubmitOptions options;
    CLI::App* submitCommand =
        app.add_subcommand("submit", "Submit a frame range: hdhair-farm submit --frames 1:96 -- stage.usda "
                                     "out.####.exr [hdhair-record options]");
    submitCommand->add_option("--frames,-f", options.frames, "Frames to render, as hdhair-record's --frames")
        ->required();
    submitCommand->add_option("--chunk", options.chunk, "Frames per array task")->capture_default_str();
    submitCommand->add_option("--tasksAtOnce", options.tasksAtOnce,
                              "At most this many tasks running at once (0: as many as Slurm fits)")
        ->capture_default_str();
    submitCommand->add_option("--partition,-p", options.partition, "sbatch --partition");
    submitCommand->add_option("--account,-A", options.account, "sbatch --account");
    submitCommand->add_option("--time,-t", options.timeLimit, "sbatch --time: each task's time limit");
    submitCommand->add_option("--mem", options.memory, "sbatch --mem: each task's memory");
    submitCommand->add_option("--cpusPerTask", options.cpusPerTask, "sbatch --cpus-per-task (0: Slurm's default)")
        ->capture_default_str();
    submitCommand->add_option("--sbatch", options.sbatchOptions,
                              "A further sbatch option, as sbatch takes it (repeatable), e.g. --sbatch=--gres=gpu:1");
    submitCommand->add_option("--retries", options.retries,
                              "Further tries of a frame the machine failed (out of memory, no GL, killed); an "
                              "error in the input is never retried")
        ->capture_default_str();
    submitCommand->add_flag("--force", options.force, "Render every frame, complete ones too");
    submitCommand->add_flag("--wait", options.wait, "Print progress until the job ends, then its report");
    submitCommand->add_option("--jobFolder", options.jobFolder,
                              "Where the job keeps its records, logs and stats (default: beside the outputs, "
                              "<name>.farm); on storage every node reaches");
    submitCommand->add_option("--record", options.record, "The hdhair-record to run (default: the one beside this)");
    submitCommand->add_option("--poll", options.pollSeconds, "--wait: seconds between looks at the queue")
        ->capture_default_str();
    submitCommand->add_option("recordArguments", options.recordArguments,
                              "hdhair-record's arguments after '--': stage, output pattern with '#', options");

    std::string statusJob;
    bool statusWait = false;
    double statusPoll = 2.0;
    CLI::App* statusCommand = app.add_subcommand("status", "Where a submitted job stands, as --wait prints it");
    statusCommand->add_option("job", statusJob, "The job id, or its job folder")->required();
    statusCommand->add_flag("--wait", statusWait, "Follow it until it ends");
    statusCommand->add_option("--poll", statusPoll, "--wait: seconds between looks at the queue")
        ->capture_default_str();

    std::string taskFolder, taskJobId;
    int taskIndex = -1;
    CLI::App* taskCommand = app.add_subcommand("task", "Render this array task's chunk (run by Slurm)");
    taskCommand->add_option("jobFolder", taskFolder, "The job folder")->required();
    taskCommand->add_option("--task", taskIndex, "The chunk (default: $SLURM_ARRAY_TASK_ID)");
    taskCommand->add_option("--jobId", taskJobId, "The job id records carry (default: $SLURM_ARRAY_JOB_ID)");

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& help) {
        return app.exit(help);
    } catch (const CLI::ParseError& error) {
        std::fprintf(stderr, "hdhair-farm: error: %s (see --help)\n", error.what());
        return 2;
    }
    try {
        if (*submitCommand) {
            if (!(options.pollSeconds > 0.0)) throw std::invalid_argument("--poll must be positive seconds");
            return submit(options);
        }
        if (*statusCommand) {
            if (!(statusPoll > 0.0)) throw std::invalid_argument("--poll must be positive seconds");
            return followJob(FarmJob::load(jobFolderOf(statusJob)), statusPoll, statusWait);
        }
        return runTask(taskFolder, taskIndex, taskJobId);
    } catch (const std::exception& error) {
        std::fprintf(stderr, "hdhair-farm: error: %s\n", error.what());
        return 1;
    }
}
