#include "hdHair/farm/JobRegistry.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "hdHair/base/AtomicFile.h"

namespace hdhair::farm {
namespace {

std::filesystem::path registryFolder() {
    if (const char* folder = std::getenv("HDHAIR_FARM_REGISTRY"); folder && *folder) return folder;
    if (const char* state = std::getenv("XDG_STATE_HOME"); state && *state)
        return std::filesystem::path(state) / "hdhair-farm" / "jobs";
    const char* home = std::getenv("HOME");
    return std::filesystem::path(home && *home ? home : "/tmp") / ".local" / "state" / "hdhair-farm" / "jobs";
}

}  // namespace

void registerJob(const std::string& jobId, const std::string& jobFolder) {
    const std::filesystem::path folder = registryFolder();
    std::filesystem::create_directories(folder);
    writeTextFileAtomically((folder / jobId).string(), jobFolder + "\n");
}

std::string jobFolderOf(const std::string& job) {
    std::error_code error;
    if (std::filesystem::is_regular_file(std::filesystem::path(job) / "job.json", error)) return job;
    if (!job.empty() && job.find_first_not_of("0123456789") == std::string::npos) {
        std::ifstream file(registryFolder() / job);
        std::string folder;
        if (file && std::getline(file, folder) && !folder.empty()) return folder;
        throw std::runtime_error("job " + job + " was not submitted by hdhair-farm from this account (nothing in " +
                                 registryFolder().string() + "); give its job folder instead");
    }
    throw std::runtime_error("'" + job + "' is neither a job id nor a job folder (one with a job.json)");
}

}  // namespace hdhair::farm
