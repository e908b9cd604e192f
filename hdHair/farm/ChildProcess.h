#pragma once
// Runs a program to its end: its standard output goes where ours goes (a
// task's log), its standard error is passed through line by line and handed
// to a callback (which keeps hdhair-record's error line), and the caller gets
// how it ended and its peak memory (wait4's rusage, that child's own).

#include <functional>
#include <string>
#include <vector>

namespace hdhair::farm {

struct ChildExit {
    int status = -1;            // exit status, or -1 when killed by a signal
    int signal = 0;             // the signal that killed it, or 0
    double seconds = 0.0;       // wall time
    long peakMemoryKB = 0;      // ru_maxrss
    bool started = false;       // false: it could not be run at all (startError says why)
    std::string startError;
};

// Throws nothing; argv[0] is the program (a path, or a name found on PATH).
// `stderrLine` gets each line without its newline; `passStderr` also writes
// them to our standard error.
ChildExit runChild(const std::vector<std::string>& argv, const std::string& workingDirectory,
                   const std::function<void(const std::string&)>& stderrLine, bool passStderr = true);

// Runs it and returns what it printed on standard output (its standard error
// to `stderrText`), for short-lived commands (sbatch, squeue, hdhair-record --check).
ChildExit captureChild(const std::vector<std::string>& argv, std::string& stdoutText, std::string& stderrText);

}  // namespace hdhair::farm
