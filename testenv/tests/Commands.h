#pragma once
// Running command-line tools from tests: hdhair-record, and OpenUSD's
// usdrecord with the HdHair plugin built here.

#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace hdhair::testenv {

// `text` as one shell word: single-quoted, its own single quotes escaped.
inline std::string shellQuoted(const std::string& text) {
    std::string out = "'";
    for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

// Runs `command` through the shell and appends what it writes to stdout and
// stderr to `output`. Returns its exit status, or -1 when it did not exit
// normally (a signal, or popen failing).
inline int runCommand(const std::string& command, std::string* output) {
    FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
    char buffer[4096];
    size_t read;
    while (pipe && (read = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) output->append(buffer, read);
    int status = pipe ? ::pclose(pipe) : -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// The start of a `usdrecord --renderer HdHair --disableGpu` command line,
// with the environment it needs set on the command itself rather than taken
// from whoever runs the tests: OpenUSD's Python modules (usdrecord is a
// Python script) and this build's plugin. `pxrBin` and `pxrPythonPath` come
// from CMake (HDHAIR_PXR_BIN, HDHAIR_PXR_PYTHONPATH), `pluginResources` is
// HDHAIR_PLUGIN_RESOURCES.
inline std::string usdrecordWithHdHair(const std::string& pxrBin, const std::string& pxrPythonPath,
                                       const std::string& pluginResources) {
    return "PYTHONPATH='" + pxrPythonPath + "' PXR_PLUGINPATH_NAME='" + pluginResources + "' '" + pxrBin +
           "/usdrecord' --renderer HdHair --disableGpu";
}

}  // namespace hdhair::testenv
