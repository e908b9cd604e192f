#include "hdHair/farm/FarmJob.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "hdHair/base/AtomicFile.h"
#include "hdHair/base/FrameSpec.h"

namespace hdhair::farm {

int FarmJob::taskCount() const {
    const size_t frames = framesToRender.size(), size = size_t(std::max(chunkSize, 1));
    return int((frames + size - 1) / size);
}

std::vector<double> FarmJob::chunk(int task) const {
    const size_t size = size_t(std::max(chunkSize, 1));
    if (task < 0 || size_t(task) * size >= framesToRender.size()) return {};
    const auto begin = framesToRender.begin() + std::ptrdiff_t(size_t(task) * size);
    const auto end = framesToRender.begin() + std::ptrdiff_t(std::min(framesToRender.size(), size_t(task + 1) * size));
    return std::vector<double>(begin, end);
}

int FarmJob::taskOf(double frame) const {
    const auto found = std::find(framesToRender.begin(), framesToRender.end(), frame);
    if (found == framesToRender.end()) return -1;
    return int(size_t(found - framesToRender.begin()) / size_t(std::max(chunkSize, 1)));
}

std::string FarmJob::outputOf(double frame) const { return expandFramePlaceholder(outputPattern, frame); }

std::string FarmJob::taskLog(int task) const { return fmt::format("{}/logs/task-{}.log", jobFolder, task); }

std::string FarmJob::statsFile(double frame) const { return fmt::format("{}/stats/{}.json", jobFolder, frameName(frame)); }

std::string FarmJob::recordFile(double frame) const {
    return fmt::format("{}/frames/{}.json", jobFolder, frameName(frame));
}

void FarmJob::save() const {
    nlohmann::json json;
    json["recordExecutable"] = recordExecutable;
    json["recordArguments"] = recordArguments;
    json["outputPattern"] = outputPattern;
    json["workingDirectory"] = workingDirectory;
    json["allFrames"] = allFrames;
    json["framesToRender"] = framesToRender;
    json["chunkSize"] = chunkSize;
    json["imageWidth"] = imageWidth;
    json["imageHeight"] = imageHeight;
    json["retries"] = retries;
    json["force"] = force;
    json["slurmJobIds"] = slurmJobIds;
    writeTextFileAtomically(jobFile(), json.dump(2) + "\n");
}

FarmJob FarmJob::load(const std::string& folder) {
    FarmJob job;
    job.jobFolder = std::filesystem::absolute(folder).lexically_normal().string();
    if (!job.jobFolder.empty() && job.jobFolder.back() == '/') job.jobFolder.pop_back();
    std::ifstream file(job.jobFile());
    if (!file) throw std::runtime_error("'" + folder + "' is not an hdhair-farm job folder (no job.json)");
    const nlohmann::json json = nlohmann::json::parse(file, nullptr, false);
    if (json.is_discarded() || !json.is_object()) throw std::runtime_error(job.jobFile() + ": not valid JSON");
    try {
        job.recordExecutable = json.at("recordExecutable").get<std::string>();
        job.recordArguments = json.at("recordArguments").get<std::vector<std::string>>();
        job.outputPattern = json.at("outputPattern").get<std::string>();
        job.workingDirectory = json.at("workingDirectory").get<std::string>();
        job.allFrames = json.at("allFrames").get<std::vector<double>>();
        job.framesToRender = json.at("framesToRender").get<std::vector<double>>();
        job.chunkSize = json.at("chunkSize").get<int>();
        job.imageWidth = json.at("imageWidth").get<int>();
        job.imageHeight = json.at("imageHeight").get<int>();
        job.retries = json.at("retries").get<int>();
        job.force = json.at("force").get<bool>();
        job.slurmJobIds = json.at("slurmJobIds").get<std::vector<std::string>>();
    } catch (const nlohmann::json::exception& error) {
        throw std::runtime_error(job.jobFile() + ": " + error.what());
    }
    return job;
}

std::string defaultJobFolder(const std::string& outputPattern) {
    const std::filesystem::path pattern(outputPattern);
    std::string stem = pattern.filename().string();
    stem = stem.substr(0, stem.find('#'));
    while (!stem.empty() && (stem.back() == '.' || stem.back() == '_' || stem.back() == '-')) stem.pop_back();
    if (stem.empty()) stem = "frames";
    return (pattern.parent_path() / (stem + ".farm")).string();
}

// The shortest text that reads back as the same frame (formatFrameSpec's),
// so that no two frames share a record.
std::string frameName(double frame) { return fmt::format("{}", frame); }

}  // namespace hdhair::farm
