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
    std::vector<char*> argv;
    for (std::string& argument : arguments) argv.push_back(argument.data());
    argv.push_back(nullptr);
    // Blender's own temporary folder goes inside the scene's, so that a
    // stopped Blender (which leaves it behind) leaves nothing once the
    // caller removes that folder. Made before fork: the child only execs.
    std::vector<std::string> environment;
    for (char** variable = environ; *variable; ++variable)
        if (std::strncmp(*variable, "TMPDIR=", 7) != 0) environment.emplace_back(*variable);
    environment.push_back("TMPDIR=" + std::filesystem::path(request.sceneJson).parent_path().string());
    std::vector<char*> envp;
    for (std::string& variable : environment) envp.push_back(variable.data());
    envp.push_back(nullptr);
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
        execvpe(argv[0], argv.data(), envp.data());
        _exit(kExecFailed);
    }
    close(pipeFds[1]);

    CyclesProcessResult result;
    std::string pending, scriptError, lastLines;
    const std::regex sample(R"(Sample (\d+)/(\d+))");
    const std::regex remaining(R"(Remaining:([0-9:.]+))");
    const std::regex version(R"(^(Blender \d+\.\d+\.\d+))");
    const std::regex done(R"(hdhair-cycles: done seconds=([0-9.]+))");
    auto handleLine = [&](const std::string& line) {
        std::smatch match;
        if (result.blenderVersion.empty() && std::regex_search(line, match, version)) result.blenderVersion = match[1];
        if (std::regex_search(line, match, done)) {
            result.renderSeconds = std::stod(match[1]);
        }
        if (line.rfind("hdhair-cycles: error: ", 0) == 0) scriptError = line.substr(22);
        if (std::regex_search(line, match, sample)) {
            CyclesProgress progress;
            progress.sample = std::stoi(match[1]);
            progress.samples = std::stoi(match[2]);
            if (std::smatch left; std::regex_search(line, left, remaining)) progress.secondsLeft = parseClock(left[1]);
            result.samplesDone = std::max(result.samplesDone, progress.sample);
            if (request.progress) request.progress(progress);
        }
        if (!line.empty()) {
            lastLines += line + "\n";
            if (lastLines.size() > 4000) lastLines.erase(0, lastLines.size() - 4000);
        }
    };

    bool stopped = false;
    char buffer[4096];
    while (true) {
        if (request.stop && request.stop->load()) {
            stopped = true;
            kill(child, SIGTERM);
            break;
        }
        pollfd descriptor{pipeFds[0], POLLIN, 0};
        const int ready = poll(&descriptor, 1, 200);
        if (ready < 0 && errno == EINTR) continue;
        if (ready <= 0) continue;
        const ssize_t count = read(pipeFds[0], buffer, sizeof buffer);
        if (count < 0 && errno == EINTR) continue;
        if (count <= 0) break;
        pending.append(buffer, size_t(count));
        for (size_t end; (end = pending.find_first_of("\r\n")) != std::string::npos;) {
            handleLine(pending.substr(0, end));
            pending.erase(0, end + 1);
        }
    }
    if (!pending.empty()) handleLine(pending);
    close(pipeFds[0]);
    int status = 0;
    while (waitpid(child, &status, 0) < 0 && errno == EINTR) {
    }
    if (stopped) throw CyclesStopped();
    if (WIFEXITED(status) && WEXITSTATUS(status) == kExecFailed && result.blenderVersion.empty())
        throw std::runtime_error("cannot run Blender ('" + request.blender +
                                 "'): install Debian's 'blender' package (scripts/debian-packages.txt) or pass "
                                 "--blender PATH");
    if (!scriptError.empty()) throw std::runtime_error("Cycles: " + scriptError);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        std::string last = lastLines;
        while (!last.empty() && last.back() == '\n') last.pop_back();
        const size_t lineStart = last.rfind('\n');
        throw std::runtime_error("Blender failed (" +
                                 (WIFEXITED(status) ? "exit status " + std::to_string(WEXITSTATUS(status))
                                                    : "signal " + std::to_string(WTERMSIG(status))) +
                                 "): " + (lineStart == std::string::npos ? last : last.substr(lineStart + 1)));
    }
    return result;
}

}  // namespace hdhair
