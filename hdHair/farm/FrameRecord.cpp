#include "hdHair/farm/FrameRecord.h"

#include <fstream>

#include <nlohmann/json.hpp>

#include "hdHair/base/AtomicFile.h"
#include "hdHair/farm/FarmJob.h"

namespace hdhair::farm {

const char* toString(FrameState state) {
    switch (state) {
    case FrameState::Running: return "running";
    case FrameState::Done: return "done";
    case FrameState::Failed: return "failed";
    }
    return "?";
}

void writeFrameRecord(const FarmJob& job, const FrameRecord& record) {
    nlohmann::json json;
    json["frame"] = record.frame;
    json["state"] = toString(record.state);
    json["slurmJobId"] = record.slurmJobId;
    json["task"] = record.task;
    json["log"] = record.log;
    json["rendered"] = record.rendered;
    json["attempts"] = record.attempts;
    json["seconds"] = record.seconds;
    json["peakMemoryKB"] = record.peakMemoryKB;
    json["error"] = record.error;
    json["inputError"] = record.inputError;
    writeTextFileAtomically(job.recordFile(record.frame), json.dump(2) + "\n");
}

std::optional<FrameRecord> readFrameRecord(const FarmJob& job, double frame) {
    std::ifstream file(job.recordFile(frame));
    if (!file) return std::nullopt;
    const nlohmann::json json = nlohmann::json::parse(file, nullptr, false);
    // Records are written atomically; one that does not parse was not
    // written by a task, and counts as no record.
    if (json.is_discarded() || !json.is_object()) return std::nullopt;
    FrameRecord record;
    record.frame = frame;
    const std::string state = json.value("state", "");
    if (state == "done") record.state = FrameState::Done;
    else if (state == "failed") record.state = FrameState::Failed;
    else if (state == "running") record.state = FrameState::Running;
    else return std::nullopt;
    record.slurmJobId = json.value("slurmJobId", "");
    record.task = json.value("task", -1);
    record.log = json.value("log", "");
    record.rendered = json.value("rendered", false);
    record.attempts = json.value("attempts", 0);
    record.seconds = json.value("seconds", 0.0);
    record.peakMemoryKB = json.value("peakMemoryKB", 0L);
    record.error = json.value("error", "");
    record.inputError = json.value("inputError", false);
    return record;
}

}  // namespace hdhair::farm
