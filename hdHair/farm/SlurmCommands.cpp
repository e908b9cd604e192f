#include "hdHair/farm/SlurmCommands.h"

#include <sstream>
#include <stdexcept>

#include "hdHair/farm/ChildProcess.h"

namespace hdhair::farm {
namespace {

// The last non-empty line a command printed: Slurm's commands end with the
// reason ("sbatch: error: Batch job submission failed: ...").
std::string lastLine(const std::string& text) {
    std::istringstream lines(text);
    std::string line, last;
    while (std::getline(lines, line))
        if (!line.empty()) last = line;
    return last;
}

std::string howItFailed(const std::string& command, const ChildExit& exit, const std::string& errors) {
    if (!exit.started) return exit.startError + " (is Slurm's client, the slurm-client package, installed?)";
    const std::string line = lastLine(errors);
    if (!line.empty()) return line;
    return command + (exit.signal ? " was killed by signal " + std::to_string(exit.signal)
                                  : " exited with status " + std::to_string(exit.status));
}

}  // namespace

std::vector<std::string> sbatchArguments(const ArrayJobRequest& request) {
    std::vector<std::string> args = {"sbatch", "--parsable", "--job-name=" + request.jobName};
    std::string array = "--array=0-" + std::to_string(request.tasks - 1);
    if (request.tasksAtOnce > 0) array += "%" + std::to_string(request.tasksAtOnce);
    args.push_back(array);
    args.push_back("--output=" + request.logPattern);
    args.push_back("--chdir=" + request.workingDirectory);
    if (!request.partition.empty()) args.push_back("--partition=" + request.partition);
    if (!request.account.empty()) args.push_back("--account=" + request.account);
    if (!request.timeLimit.empty()) args.push_back("--time=" + request.timeLimit);
    if (!request.memory.empty()) args.push_back("--mem=" + request.memory);
    if (request.cpusPerTask > 0) args.push_back("--cpus-per-task=" + std::to_string(request.cpusPerTask));
    args.insert(args.end(), request.extraOptions.begin(), request.extraOptions.end());
    args.push_back("--wrap=" + request.taskCommand);
    return args;
}

std::string submitArrayJob(const ArrayJobRequest& request) {
    std::string output, errors;
    const ChildExit exit = captureChild(sbatchArguments(request), output, errors);
    if (!exit.started || exit.status != 0) throw std::runtime_error(howItFailed("sbatch", exit, errors));
    // --parsable prints "id" or "id;cluster".
    std::string id = lastLine(output);
    id = id.substr(0, id.find(';'));
    if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
        throw std::runtime_error("sbatch printed no job id (it printed '" + lastLine(output) + "')");
    return id;
}

std::vector<QueuedTask> parseQueuedTasks(const std::string& squeueOutput, const std::string& jobId) {
    std::vector<QueuedTask> tasks;
    std::istringstream lines(squeueOutput);
    std::string line;
    while (std::getline(lines, line)) {
        const size_t bar = line.find('|');
        if (bar == std::string::npos) continue;
        const std::string id = line.substr(0, bar);
        if (id.rfind(jobId + "_", 0) != 0) continue;
        const std::string index = id.substr(jobId.size() + 1);
        if (index.empty() || index.find_first_not_of("0123456789") != std::string::npos) continue;
        tasks.push_back({std::stoi(index), line.substr(bar + 1)});
    }
    return tasks;
}

std::optional<std::vector<QueuedTask>> queuedTasks(const std::string& jobId, std::string& error) {
    std::string output, errors;
    const ChildExit exit = captureChild({"squeue", "-h", "-r", "-j", jobId, "-o", "%i|%T"}, output, errors);
    if (exit.started && exit.status != 0 && errors.find("Invalid job id") != std::string::npos)
        return std::vector<QueuedTask>();  // ended, and gone from the controller's memory
    if (!exit.started || exit.status != 0) {
        error = howItFailed("squeue", exit, errors);
        return std::nullopt;
    }
    return parseQueuedTasks(output, jobId);
}

std::string shellQuoted(const std::string& word) {
    std::string quoted = "'";
    for (char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

}  // namespace hdhair::farm
