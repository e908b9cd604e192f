#include "hdHair/base/AvailableMemory.h"

#include <sys/resource.h>

#include <fstream>
#include <sstream>

#include <fmt/format.h>

namespace hdhair {
namespace {

// The first number in `path` (memory.max holds "max" when unlimited).
bool readNumber(const std::string& path, uint64_t* value) {
    std::ifstream file(path);
    return bool(file >> *value);
}

// A "Key:   N kB" line of /proc/self/status or /proc/meminfo, in bytes.
bool readKilobytes(const std::string& path, const std::string& key, uint64_t* bytes) {
    std::ifstream file(path);
    std::string line;
    while (std::getline(file, line)) {
        if (line.rfind(key + ":", 0) != 0) continue;
        std::istringstream fields(line.substr(key.size() + 1));
        uint64_t kilobytes = 0;
        if (!(fields >> kilobytes)) return false;
        *bytes = kilobytes * 1024;
        return true;
    }
    return false;
}

// The process's cgroup (v2: "0::/path") folder.
std::string cgroupFolder() {
    std::ifstream file("/proc/self/cgroup");
    std::string line;
    while (std::getline(file, line))
        if (line.rfind("0::", 0) == 0) return "/sys/fs/cgroup" + line.substr(3);
    return std::string();
}

}  // namespace

AvailableMemory availableMemory() {
    AvailableMemory available;
    auto consider = [&](uint64_t bytes, const char* what) {
        if (bytes < available.bytes) {
            available.bytes = bytes;
            available.limitedBy = what;
        }
    };
    uint64_t bytes = 0;
    if (readKilobytes("/proc/meminfo", "MemAvailable", &bytes)) consider(bytes, "MemAvailable");
    if (const std::string folder = cgroupFolder(); !folder.empty()) {
        uint64_t limit = 0, current = 0;
        if (readNumber(folder + "/memory.max", &limit) && readNumber(folder + "/memory.current", &current))
            consider(limit > current ? limit - current : 0, "the cgroup's memory.max");
    }
    rlimit limit{};
    uint64_t addressSpace = 0;
    if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY &&
        readKilobytes("/proc/self/status", "VmSize", &addressSpace))
        consider(limit.rlim_cur > addressSpace ? limit.rlim_cur - addressSpace : 0, "ulimit -v");
    return available;
}

std::string describeBytes(uint64_t bytes) {
    const double megabytes = double(bytes) / (1024.0 * 1024.0);
    return megabytes >= 1024.0 ? fmt::format("{:.1f} GB", megabytes / 1024.0) : fmt::format("{:.0f} MB", megabytes);
}

}  // namespace hdhair
