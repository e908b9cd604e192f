#include "hdHair/reference/CyclesProcess.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <regex>
#include <vector>

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

namespace hdhair {
namespace {

// The exit status the child uses when exec fails: the shell's "not found".
constexpr int kExecFailed = 127;

double parseClock(const std::string& text) {
    // Blender's "HH:MM:SS.ss", "MM:SS.ss" or "SS.ss".
    double seconds = 0.0;
    size_t start = 0;
    while (true) {
        const size_t colon = text.find(':', start);
        seconds = seconds * 60.0 + std::atof(text.substr(start, colon - start).c_str());
        if (colon == std::string::npos) break;
        start = colon + 1;
    }
    return seconds;
}

// Null-terminated pointers into `strings`, as execvpe takes them.
std::vector<char*> pointersTo(std::vector<std::string>& strings) {
    std::vector<char*> pointers;
    for (std::string& text : strings) pointers.push_back(text.data());
    pointers.push_back(nullptr);
    return pointers;
}

// Blender's own temporary folder goes inside the scene's, so that a
// stopped Blender (which leaves it behind) leaves nothing once the
// caller removes that folder. Made before fork: the child only execs.
std::vector<std::string> blenderEnvironment(const std::string& sceneJson) {
    std::vector<std::string> environment;
    for (char** variable = environ; *variable; ++variable)
        if (std::strncmp(*variable, "TMPDIR=", 7) != 0) environment.emplace_back(*variable);
    environment.push_back("TMPDIR=" + std::filesystem::path(sceneJson).parent_path().string());
    return environment;
}

// Forks Blender with its output (stdout and stderr) on the pipe's write end,
// which the parent then closes.
pid_t startBlender(char* const* argv, char* const* envp, const int pipeFds[2]) {
    const pid_t child = fork();
    if (child < 0) throw std::runtime_error(std::string("cannot start Blender: ") + std::strerror(errno));
    if (child == 0) {
        dup2(pipeFds[1], STDOUT_FILENO);
        dup2(pipeFds[1], STDERR_FILENO);
        close(pipeFds[0]);
        close(pipeFds[1]);
        // Blender must not read the caller's terminal.
        const int devNull = open("/dev/null", O_RDONLY);
        if (devNull >= 0) dup2(devNull, STDIN_FILENO);
        execvpe(argv[0], argv, envp);
        _exit(kExecFailed);
    }
    close(pipeFds[1]);
    return child;
}

// What Blender's output says, line by line: its version, its progress, the
// script's result or error, and its last lines for a failure's reason.
class BlenderOutput {
public:
    explicit BlenderOutput(const CyclesProcessRequest& request) : request_(request) {}

    void handleLine(const std::string& line) {
        std::smatch match;
        if (result.blenderVersion.empty() && std::regex_search(line, match, version_)) result.blenderVersion = match[1];
        if (std::regex_search(line, match, done_)) {
            result.renderSeconds = std::stod(match[1]);
        }
        if (line.rfind("hdhair-cycles: error: ", 0) == 0) scriptError = line.substr(22);
        if (std::regex_search(line, match, sample_)) {
            CyclesProgress progress;
            progress.sample = std::stoi(match[1]);
            progress.samples = std::stoi(match[2]);
            if (std::smatch left; std::regex_search(line, left, remaining_)) progress.secondsLeft = parseClock(left[1]);
            result.samplesDone = std::max(result.samplesDone, progress.sample);
            if (request_.progress) request_.progress(progress);
        }
        if (!line.empty()) {
            lastLines += line + "\n";
            if (lastLines.size() > 4000) lastLines.erase(0, lastLines.size() - 4000);
        }
    }

    CyclesProcessResult result;
    std::string scriptError, lastLines;

private:
    const CyclesProcessRequest& request_;
    const std::regex sample_{R"(Sample (\d+)/(\d+))"};
    const std::regex remaining_{R"(Remaining:([0-9:.]+))"};
    const std::regex version_{R"(^(Blender \d+\.\d+\.\d+))"};
    const std::regex done_{R"(hdhair-cycles: done seconds=([0-9.]+))"};
};

// Reads Blender's output until it closes it, or until the caller asks to
// stop (Blender then gets SIGTERM); returns whether it was stopped.
bool followBlender(int fd, pid_t child, const std::atomic<bool>* stop, BlenderOutput& output) {
    std::string pending;
    bool stopped = false;
    char buffer[4096];
    while (true) {
        if (stop && stop->load()) {
            stopped = true;
            kill(child, SIGTERM);
            break;
        }
        pollfd descriptor{fd, POLLIN, 0};
        const int ready = poll(&descriptor, 1, 200);
        if (ready < 0 && errno == EINTR) continue;
        if (ready <= 0) continue;
        const ssize_t count = read(fd, buffer, sizeof buffer);
        if (count < 0 && errno == EINTR) continue;
        if (count <= 0) break;
        pending.append(buffer, size_t(count));
        for (size_t end; (end = pending.find_first_of("\r\n")) != std::string::npos;) {
            output.handleLine(pending.substr(0, end));
            pending.erase(0, end + 1);
        }
    }
    if (!pending.empty()) output.handleLine(pending);
    return stopped;
}

int waitForExit(pid_t child) {
    int status = 0;
    while (waitpid(child, &status, 0) < 0 && errno == EINTR) {
    }
    return status;
}

// The last line of `lines`, trailing newlines left off.
std::string lastLineOf(const std::string& lines) {
    std::string last = lines;
    while (!last.empty() && last.back() == '\n') last.pop_back();
    const size_t lineStart = last.rfind('\n');
    return lineStart == std::string::npos ? last : last.substr(lineStart + 1);
}

// Throws the one-line reason for a Blender that could not run or failed.
void checkBlenderSucceeded(int status, const std::string& blender, const BlenderOutput& output) {
    if (WIFEXITED(status) && WEXITSTATUS(status) == kExecFailed && output.result.blenderVersion.empty())
        throw std::runtime_error("cannot run Blender ('" + blender +
                                 "'): install Debian's 'blender' package (scripts/debian-packages.txt) or pass "
                                 "--blender PATH");
    if (!output.scriptError.empty()) throw std::runtime_error("Cycles: " + output.scriptError);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        throw std::runtime_error("Blender failed (" +
                                 (WIFEXITED(status) ? "exit status " + std::to_string(WEXITSTATUS(status))
                                                    : "signal " + std::to_string(WTERMSIG(status))) +
                                 "): " + lastLineOf(output.lastLines));
}

}  // namespace

std::string defaultCyclesScript() {
    if (const char* path = std::getenv("HDHAIR_CYCLES_SCRIPT")) return path;
    std::error_code error;
    const std::filesystem::path executable = std::filesystem::read_symlink("/proc/self/exe", error);
    if (error) return "renderCyclesScene.py";
    return (executable.parent_path().parent_path() / "share" / "hdhair" / "cycles" / "renderCyclesScene.py").string();
}

CyclesProcessResult runCyclesProcess(const CyclesProcessRequest& request) {
    if (!std::filesystem::is_regular_file(request.script))
        throw std::runtime_error("the Cycles scene script '" + request.script +
                                 "' is missing (set HDHAIR_CYCLES_SCRIPT, or reinstall hdHair)");
    int pipeFds[2];
    if (pipe(pipeFds) != 0) throw std::runtime_error(std::string("cannot start Blender: ") + std::strerror(errno));
    std::vector<std::string> arguments = {request.blender, "-b", "--factory-startup", "--python-exit-code", "2",
                                          "-P", request.script, "--", request.sceneJson, request.outputExr};
    std::vector<char*> argv = pointersTo(arguments);
    std::vector<std::string> environment = blenderEnvironment(request.sceneJson);
    std::vector<char*> envp = pointersTo(environment);
    const pid_t child = startBlender(argv.data(), envp.data(), pipeFds);

    BlenderOutput output(request);
    const bool stopped = followBlender(pipeFds[0], child, request.stop, output);
    close(pipeFds[0]);
    const int status = waitForExit(child);
    if (stopped) throw CyclesStopped();
    checkBlenderSucceeded(status, request.blender, output);
    return output.result;
}

}  // namespace hdhair
