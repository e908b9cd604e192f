#pragma once
// Runs a shell command for tests that drive hdHair's programs and OpenUSD's
// (hdhair-record, usdrecord, usdview) the way a user does.

#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace hdhair::testenv {

struct CommandRun {
    int exitCode = -1;   // -1 when it could not start or did not exit normally
    std::string output;  // stdout and stderr together
};

inline CommandRun runCommand(const std::string& command) {
    CommandRun run;
    FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
    if (!pipe) return run;
    char buffer[4096];
    size_t read;
    while ((read = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) run.output.append(buffer, read);
    int status = ::pclose(pipe);
    run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return run;
}

}  // namespace hdhair::testenv
