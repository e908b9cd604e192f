#include "hdHair/farm/FarmProgress.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "hdHair/farm/FarmJob.h"
#include "hdHair/base/FrameSpec.h"

namespace hdhair::farm {
namespace {

double median(std::vector<double> values) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    const size_t middle = values.size() / 2;
    return values.size() % 2 ? values[middle] : 0.5 * (values[middle - 1] + values[middle]);
}

std::string describeSeconds(double seconds) {
    if (seconds < 90.0) return fmt::format("{:.0f} s", seconds);
    if (seconds < 5400.0) return fmt::format("{:.0f} min", seconds / 60.0);
    return fmt::format("{:.1f} h", seconds / 3600.0);
}

}  // namespace

std::vector<double> FarmProgress::framesToResubmit() const {
    std::vector<double> frames = notRendered;
    for (const FrameRecord& failure : failures) frames.push_back(failure.frame);
    std::sort(frames.begin(), frames.end());
    return frames;
}

FarmProgress measureProgress(const FarmJob& job, const std::optional<std::vector<QueuedTask>>& queue,
                             const std::string& queueError) {
    FarmProgress progress;
    progress.total = int(job.allFrames.size());
    progress.queueKnown = queue.has_value();
    progress.queueError = queueError;
    // Without squeue's answer the job counts as active: nothing is called
    // lost while Slurm cannot be asked.
    progress.jobActive = !queue || !queue->empty();
    if (queue)
        for (const QueuedTask& task : *queue) {
            if (task.state == "RUNNING" || task.state == "COMPLETING") ++progress.tasksRunning;
            else if (task.state == "PENDING") ++progress.tasksPending;
        }
    const std::string jobId = job.latestJobId();
    std::vector<double> seconds;
    // Looked up once a frame on every poll: sorted, not scanned.
    std::vector<double> toRender = job.framesToRender;
    std::sort(toRender.begin(), toRender.end());
    for (double frame : job.allFrames) {
        if (!std::binary_search(toRender.begin(), toRender.end(), frame)) {
            ++progress.done;  // complete when this job was submitted
            continue;
        }
        const std::optional<FrameRecord> record = readFrameRecord(job, frame);
        const bool ours = record && record->slurmJobId == jobId;
        if (ours && record->state == FrameState::Done) {
            ++progress.done;
            if (record->rendered) {
                ++progress.rendered;
                progress.renderedRecords.push_back(*record);
                seconds.push_back(record->seconds);
            }
        } else if (ours && record->state == FrameState::Failed) {
            ++progress.failed;
            progress.failures.push_back(*record);
        } else if (progress.jobActive) {
            ++(ours ? progress.running : progress.waiting);
        } else {
            progress.notRendered.push_back(frame);
        }
    }
    // Frames left, at the median frame time, over the tasks running now.
    const int left = progress.running + progress.waiting;
    if (!seconds.empty() && progress.jobActive)
        progress.secondsLeft = left * median(seconds) / std::max(1, progress.tasksRunning);
    return progress;
}

std::string progressLine(const FarmJob& job, const FarmProgress& progress) {
    std::string line = fmt::format("hdhair-farm: job {}: {}/{} frames done, {} running, {} failed", job.latestJobId(),
                                   progress.done, progress.total, progress.running, progress.failed);
    if (progress.waiting) line += fmt::format(", {} waiting", progress.waiting);
    if (!progress.notRendered.empty()) line += fmt::format(", {} not rendered", progress.notRendered.size());
    if (!progress.queueKnown) line += " (Slurm not answering: " + progress.queueError + ")";
    else if (!progress.jobActive) line += "; the job has ended";
    else if (progress.secondsLeft >= 0.0) line += "; about " + describeSeconds(progress.secondsLeft) + " left";
    return line;
}

nlohmann::json frameTimeSummary(const FarmProgress& progress) {
    std::vector<FrameRecord> records = progress.renderedRecords;
    std::vector<double> seconds;
    long peakKB = 0;
    for (const FrameRecord& record : records) {
        seconds.push_back(record.seconds);
        peakKB = std::max(peakKB, record.peakMemoryKB);
    }
    std::sort(records.begin(), records.end(),
              [](const FrameRecord& a, const FrameRecord& b) { return a.seconds > b.seconds; });
    nlohmann::json slowest = nlohmann::json::array();
    for (size_t i = 0; i < std::min<size_t>(3, records.size()); ++i)
        slowest.push_back({{"frame", records[i].frame}, {"seconds", records[i].seconds}, {"task", records[i].task}});
    double total = 0.0;
    for (double s : seconds) total += s;
    return {{"framesRendered", seconds.size()},
            {"totalSeconds", total},
            {"medianSeconds", median(seconds)},
            {"peakMemoryMB", double(peakKB) / 1024.0},
            {"slowest", slowest}};
}

std::string finalReport(const FarmJob& job, const FarmProgress& progress) {
    std::string report;
    for (const FrameRecord& failure : progress.failures)
        report += fmt::format("hdhair-farm: frame {} failed in task {} (log {}): {}\n", frameName(failure.frame),
                              failure.task, failure.log, failure.error);
    if (!progress.notRendered.empty())
        report += fmt::format("hdhair-farm: frames {} were not rendered: the job ended before them (cancelled, or a "
                              "task was killed; see {}/logs)\n",
                              formatFrameSpec(progress.notRendered), job.jobFolder);
    const nlohmann::json summary = frameTimeSummary(progress);
    if (summary["framesRendered"].get<size_t>() > 0) {
        std::string slowest;
        for (const nlohmann::json& frame : summary["slowest"])
            slowest += fmt::format("{}{} ({:.2f} s)", slowest.empty() ? "" : ", ",
                                   frameName(frame["frame"].get<double>()), frame["seconds"].get<double>());
        report += fmt::format("hdhair-farm: {} frames rendered, {:.1f} s of frame time in all, median {:.2f} s, peak "
                              "memory {:.0f} MB; slowest {}\n",
                              summary["framesRendered"].get<size_t>(), summary["totalSeconds"].get<double>(),
                              summary["medianSeconds"].get<double>(), summary["peakMemoryMB"].get<double>(), slowest);
    }
    const std::vector<double> again = progress.framesToResubmit();
    if (!again.empty())
        report += fmt::format("hdhair-farm: to render the missing frames again: hdhair-farm submit --frames {} ...\n",
                              formatFrameSpec(again));
    else if (progress.complete())
        report += fmt::format("hdhair-farm: all {} frames complete\n", progress.total);
    return report;
}

}  // namespace hdhair::farm
