#pragma once
// How much memory this process can still take, so that a request far past
// it (an image 16384 pixels across) is refused with the sizes in one line
// before anything is allocated, rather than dying in std::bad_alloc or the
// kernel's OOM killer.

#include <cstdint>
#include <string>

namespace hdhair {

struct AvailableMemory {
    uint64_t bytes = UINT64_MAX;
    std::string limitedBy;  // "MemAvailable", "the cgroup's memory.max", "ulimit -v"
};

// The least of: the system's MemAvailable (/proc/meminfo), what the cgroup's
// memory.max leaves above memory.current, and what RLIMIT_AS leaves above
// this process's address space. Unknown parts are left out.
AvailableMemory availableMemory();

// "17.2 GB", "512 MB": sizes for messages.
std::string describeBytes(uint64_t bytes);

}  // namespace hdhair
