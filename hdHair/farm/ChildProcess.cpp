#include "hdHair/farm/ChildProcess.h"

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace hdhair::farm {
namespace {

struct Pipe {
    int read = -1, write = -1;
    bool open() {
        int ends[2];
        if (pipe2(ends, O_CLOEXEC) != 0) return false;
        read = ends[0];
        write = ends[1];
        return true;
    }
    ~Pipe() {
        if (read >= 0) close(read);
        if (write >= 0) close(write);
    }
};

// Starts argv with stdout and stderr redirected to the given descriptors (-1:
// inherited), in `workingDirectory` when not empty.
pid_t spawn(const std::vector<std::string>& argv, const std::string& workingDirectory, int stdoutFd, int stderrFd,
            std::string& error) {
    std::vector<char*> args;
    for (const std::string& arg : argv) args.push_back(const_cast<char*>(arg.c_str()));
    args.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    if (stdoutFd >= 0) posix_spawn_file_actions_adddup2(&actions, stdoutFd, STDOUT_FILENO);
    if (stderrFd >= 0) posix_spawn_file_actions_adddup2(&actions, stderrFd, STDERR_FILENO);
    if (!workingDirectory.empty()) posix_spawn_file_actions_addchdir_np(&actions, workingDirectory.c_str());
    pid_t pid = -1;
    const int result = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (result != 0) {
        error = "cannot run '" + argv[0] + "': " + std::strerror(result);
        return -1;
    }
    return pid;
}

void waitFor(pid_t pid, ChildExit& exit) {
    int status = 0;
    struct rusage usage {};
    while (wait4(pid, &status, 0, &usage) < 0 && errno == EINTR) {}
    exit.peakMemoryKB = usage.ru_maxrss;
    if (WIFEXITED(status)) exit.status = WEXITSTATUS(status);
    else if (WIFSIGNALED(status)) exit.signal = WTERMSIG(status);
}

// Reads both pipes (-1: none) until they close, handing the text to the sinks.
void drain(int first, const std::function<void(const char*, size_t)>& firstSink, int second,
           const std::function<void(const char*, size_t)>& secondSink) {
    struct pollfd fds[2] = {{first, POLLIN, 0}, {second, POLLIN, 0}};
    int open = (first >= 0) + (second >= 0);
    char buffer[4096];
    while (open > 0) {
        if (poll(fds, 2, -1) < 0) {
            if (errno == EINTR) continue;
            return;
        }
        for (int i = 0; i < 2; ++i) {
            if (fds[i].fd < 0 || !(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
            const ssize_t count = read(fds[i].fd, buffer, sizeof buffer);
            if (count > 0) {
                (i == 0 ? firstSink : secondSink)(buffer, size_t(count));
            } else if (count == 0 || errno != EINTR) {
                fds[i].fd = -1;
                --open;
            }
        }
    }
}

}  // namespace

ChildExit runChild(const std::vector<std::string>& argv, const std::string& workingDirectory,
                   const std::function<void(const std::string&)>& stderrLine, bool passStderr) {
    ChildExit exit;
    Pipe errors;
    if (!errors.open()) {
        exit.startError = std::string("cannot make a pipe: ") + std::strerror(errno);
        return exit;
    }
    const auto start = std::chrono::steady_clock::now();
    const pid_t pid = spawn(argv, workingDirectory, -1, errors.write, exit.startError);
    if (pid < 0) return exit;
    exit.started = true;
    close(errors.write);
    errors.write = -1;
    std::string pending;
    drain(errors.read, [&](const char* text, size_t size) {
        if (passStderr) (void)!write(STDERR_FILENO, text, size);
        pending.append(text, size);
        for (size_t newline; (newline = pending.find('\n')) != std::string::npos;) {
            stderrLine(pending.substr(0, newline));
            pending.erase(0, newline + 1);
        }
    }, -1, nullptr);
    if (!pending.empty()) stderrLine(pending);
    waitFor(pid, exit);
    exit.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return exit;
}

ChildExit captureChild(const std::vector<std::string>& argv, std::string& stdoutText, std::string& stderrText) {
    ChildExit exit;
    Pipe output, errors;
    if (!output.open() || !errors.open()) {
        exit.startError = std::string("cannot make a pipe: ") + std::strerror(errno);
        return exit;
    }
    const auto start = std::chrono::steady_clock::now();
    const pid_t pid = spawn(argv, "", output.write, errors.write, exit.startError);
    if (pid < 0) return exit;
    exit.started = true;
    close(output.write);
    output.write = -1;
    close(errors.write);
    errors.write = -1;
    drain(output.read, [&](const char* text, size_t size) { stdoutText.append(text, size); }, errors.read,
          [&](const char* text, size_t size) { stderrText.append(text, size); });
    waitFor(pid, exit);
    exit.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return exit;
}

}  // namespace hdhair::farm
