// hdhair-farm's parts without Slurm: chunks, records, completeness, retries
// and the report. testFarmSlurm.sh runs the whole tool on a real cluster.

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "hdHair/base/AtomicFile.h"
#include "hdHair/farm/ChildProcess.h"
#include "hdHair/farm/CompleteFrame.h"
#include "hdHair/farm/FarmJob.h"
#include "hdHair/farm/FarmProgress.h"
#include "hdHair/farm/FrameRecord.h"
#include "hdHair/farm/FrameTask.h"
#include "hdHair/farm/SlurmCommands.h"
#include "hdHair/image/ImageWriter.h"

namespace hdhair::farm {
namespace {

namespace fs = std::filesystem;

class FarmFolder : public ::testing::Test {
protected:
    void SetUp() override {
        folder = fs::temp_directory_path() /
                 ("hdhair-farm-test-" + std::to_string(::getpid()) + "-" +
                  ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(folder);
        for (const char* sub : {"job/frames", "job/stats", "job/logs", "out"}) fs::create_directories(folder / sub);
    }
    void TearDown() override { fs::remove_all(folder); }

    FarmJob jobOf(std::vector<double> frames, int chunk) const {
        FarmJob job;
        job.jobFolder = (folder / "job").string();
        job.outputPattern = (folder / "out" / "frame.#.exr").string();
        job.workingDirectory = folder.string();
        job.allFrames = frames;
        job.framesToRender = frames;
        job.chunkSize = chunk;
        job.imageWidth = 4;
        job.imageHeight = 3;
        job.slurmJobIds = {"41"};
        return job;
    }

    void writeFrameImage(const std::string& path, int width, int height) const {
        ImageColor color;
        writeImage(Image(width, height, 4, 0.5f), path, color);
    }

    fs::path folder;
};

TEST(FarmJob, FramesAreCutIntoChunksInOrder) {
    FarmJob job;
    job.framesToRender = {1, 2, 3, 4, 5, 6, 7};
    job.chunkSize = 3;
    EXPECT_EQ(job.taskCount(), 3);
    EXPECT_EQ(job.chunk(0), (std::vector<double>{1, 2, 3}));
    EXPECT_EQ(job.chunk(2), (std::vector<double>{7}));
    EXPECT_TRUE(job.chunk(3).empty());
    EXPECT_TRUE(job.chunk(-1).empty());
    EXPECT_EQ(job.taskOf(5), 1);
    EXPECT_EQ(job.taskOf(9), -1);
    job.chunkSize = 1;
    EXPECT_EQ(job.taskCount(), 7);
}

TEST(FarmJob, TheDefaultFolderSitsBesideTheOutputs) {
    EXPECT_EQ(defaultJobFolder("renders/bear.####.exr"), "renders/bear.farm");
    EXPECT_EQ(defaultJobFolder("renders/bear_###.png"), "renders/bear.farm");
    EXPECT_EQ(defaultJobFolder("####.exr"), "frames.farm");
    EXPECT_EQ(frameName(7), "7");
    EXPECT_EQ(frameName(7.5), "7.5");
    EXPECT_EQ(frameName(123456.5), "123456.5");
    EXPECT_EQ(frameName(1000000), "1000000");
}

TEST_F(FarmFolder, AJobReadsBackAsSaved) {
    FarmJob job = jobOf({1, 2, 3}, 2);
    job.recordExecutable = "/bin/hdhair-record";
    job.recordArguments = {"stage.usda", "out.#.exr", "-w", "64"};
    job.force = true;
    job.save();
    const FarmJob loaded = FarmJob::load(job.jobFolder);
    EXPECT_EQ(loaded.recordArguments, job.recordArguments);
    EXPECT_EQ(loaded.framesToRender, job.framesToRender);
    EXPECT_EQ(loaded.slurmJobIds, job.slurmJobIds);
    EXPECT_TRUE(loaded.force);
    EXPECT_EQ(loaded.outputOf(2), (folder / "out" / "frame.2.exr").string());
    EXPECT_THROW(FarmJob::load((folder / "out").string()), std::runtime_error);
}

TEST_F(FarmFolder, OnlyAWholeImageOfTheJobsSizeIsComplete) {
    const std::string path = (folder / "out" / "frame.1.exr").string();
    EXPECT_EQ(whyFrameIncomplete(path, 4, 3), "missing");
    writeFrameImage(path, 4, 3);
    EXPECT_EQ(whyFrameIncomplete(path, 4, 3), "");
    EXPECT_EQ(whyFrameIncomplete(path, 8, 6), "4x3, not 8x6");
    // A file cut short (written by something other than an atomic write).
    const auto size = fs::file_size(path);
    fs::resize_file(path, size / 2);
    EXPECT_NE(whyFrameIncomplete(path, 4, 3), "");
}

TEST(SlurmCommands, AnArrayJobPassesTheSitesOptionsThrough) {
    ArrayJobRequest request;
    request.jobName = "hdhair-farm:bear.farm";
    request.tasks = 24;
    request.tasksAtOnce = 2;
    request.logPattern = "/jobs/bear.farm/logs/task-%a.log";
    request.workingDirectory = "/shots/a";
    request.taskCommand = "exec '/bin/hdhair-farm' task '/jobs/bear.farm'";
    request.partition = "gpu";
    request.account = "show";
    request.timeLimit = "1:00:00";
    request.memory = "8G";
    request.cpusPerTask = 4;
    request.extraOptions = {"--gres=gpu:1", "--qos=high"};
    const std::vector<std::string> args = sbatchArguments(request);
    const std::vector<std::string> expected = {
        "sbatch", "--parsable", "--job-name=hdhair-farm:bear.farm", "--array=0-23%2",
        "--output=/jobs/bear.farm/logs/task-%a.log", "--chdir=/shots/a", "--partition=gpu", "--account=show",
        "--time=1:00:00", "--mem=8G", "--cpus-per-task=4", "--gres=gpu:1", "--qos=high",
        "--wrap=exec '/bin/hdhair-farm' task '/jobs/bear.farm'"};
    EXPECT_EQ(args, expected);
    request.tasksAtOnce = 0;
    EXPECT_EQ(sbatchArguments(request)[3], "--array=0-23");
    EXPECT_EQ(shellQuoted("it's here"), "'it'\\''s here'");
}

TEST(SlurmCommands, QueuedTasksAreThisJobsOnly) {
    const std::vector<QueuedTask> tasks =
        parseQueuedTasks("41_3|RUNNING\n41_4|PENDING\n410_1|RUNNING\n41|PENDING\nnonsense\n41_x|RUNNING\n", "41");
    ASSERT_EQ(tasks.size(), 2u);
    EXPECT_EQ(tasks[0].task, 3);
    EXPECT_EQ(tasks[0].state, "RUNNING");
    EXPECT_EQ(tasks[1].task, 4);
    EXPECT_EQ(tasks[1].state, "PENDING");
}

TEST_F(FarmFolder, ProgressCountsFramesFromTheLatestJobsRecords) {
    FarmJob job = jobOf({1, 2, 3, 4, 5, 6}, 2);
    job.framesToRender = {2, 3, 4, 5, 6};  // frame 1 was complete at submission
    auto record = [&](double frame, FrameState state, const std::string& jobId, double seconds) {
        FrameRecord r;
        r.frame = frame;
        r.state = state;
        r.slurmJobId = jobId;
        r.task = job.taskOf(frame);
        r.log = job.taskLog(r.task);
        r.rendered = state == FrameState::Done;
        r.seconds = seconds;
        r.peakMemoryKB = long(seconds * 1024);
        if (state == FrameState::Failed) r.error = "/cam.focalLength: 0 is not a positive length";
        writeFrameRecord(job, r);
    };
    record(2, FrameState::Done, "41", 4.0);
    record(3, FrameState::Done, "41", 2.0);
    record(4, FrameState::Failed, "41", 1.0);
    record(5, FrameState::Running, "41", 0.0);
    record(6, FrameState::Done, "40", 9.0);  // an earlier job's record: not this job's frame

    FarmProgress running = measureProgress(job, std::vector<QueuedTask>{{2, "RUNNING"}});
    EXPECT_TRUE(running.jobActive);
    EXPECT_EQ(running.done, 3);
    EXPECT_EQ(running.rendered, 2);
    EXPECT_EQ(running.failed, 1);
    EXPECT_EQ(running.running, 1);
    EXPECT_EQ(running.waiting, 1);
    // Two frames left at the median of 2 and 4 seconds, on one running task.
    EXPECT_DOUBLE_EQ(running.secondsLeft, 6.0);
    EXPECT_NE(progressLine(job, running).find("3/6 frames done, 1 running, 1 failed, 1 waiting; about 6 s left"),
              std::string::npos)
        << progressLine(job, running);

    FarmProgress ended = measureProgress(job, std::vector<QueuedTask>{});
    EXPECT_FALSE(ended.jobActive);
    EXPECT_EQ(ended.notRendered, (std::vector<double>{5, 6}));
    EXPECT_EQ(ended.framesToResubmit(), (std::vector<double>{4, 5, 6}));
    EXPECT_FALSE(ended.complete());
    const std::string report = finalReport(job, ended);
    EXPECT_NE(report.find("frame 4 failed in task 1 (log " + job.taskLog(1) +
                          "): /cam.focalLength: 0 is not a positive length"),
              std::string::npos)
        << report;
    EXPECT_NE(report.find("--frames 4:6"), std::string::npos) << report;
    const nlohmann::json summary = frameTimeSummary(ended);
    EXPECT_EQ(summary["framesRendered"], 2);
    EXPECT_DOUBLE_EQ(summary["totalSeconds"].get<double>(), 6.0);
    EXPECT_DOUBLE_EQ(summary["medianSeconds"].get<double>(), 3.0);
    EXPECT_DOUBLE_EQ(summary["peakMemoryMB"].get<double>(), 4.0);
    EXPECT_EQ(summary["slowest"][0]["frame"], 2.0);

    // Without squeue's answer nothing is called lost.
    FarmProgress unknown = measureProgress(job, std::nullopt, "connection refused");
    EXPECT_TRUE(unknown.notRendered.empty());
    EXPECT_NE(progressLine(job, unknown).find("Slurm not answering: connection refused"), std::string::npos);
}

TEST_F(FarmFolder, OnlyTheFramesOwnLeftoverTemporariesAreRemoved) {
    const fs::path out = folder / "out";
    for (const char* name : {".frame.5.tmp-0a1b2c.exr", ".frame.5.tmp-ffffff.exr", ".frame.5.tmp-0a1b2.exr",
                             ".frame.55.tmp-0a1b2c.exr", ".frame.5.tmp-0a1b2c.png", ".frame.5.tmp-0a1b2g.exr",
                             "frame.5.exr"})
        std::ofstream(out / name) << name;
    EXPECT_EQ(removeLeftoverTemporaries((out / "frame.5.exr").string()), 2);
    EXPECT_FALSE(fs::exists(out / ".frame.5.tmp-0a1b2c.exr"));
    EXPECT_FALSE(fs::exists(out / ".frame.5.tmp-ffffff.exr"));
    for (const char* kept : {".frame.5.tmp-0a1b2.exr", ".frame.55.tmp-0a1b2c.exr", ".frame.5.tmp-0a1b2c.png",
                             ".frame.5.tmp-0a1b2g.exr", "frame.5.exr"})
        EXPECT_TRUE(fs::exists(out / kept)) << kept;
    EXPECT_EQ(removeLeftoverTemporaries((folder / "missing" / "frame.5.exr").string()), 0);
}

TEST(FrameTask, OnlyTheMachinesFailuresAreRetried) {
    EXPECT_TRUE(isMachineFailure(75, 0));
    EXPECT_TRUE(isMachineFailure(-1, SIGKILL));
    EXPECT_FALSE(isMachineFailure(1, 0));
    EXPECT_FALSE(isMachineFailure(2, 0));
}

TEST(ChildProcess, StandardErrorLinesAndTheExitReachTheCaller) {
    std::vector<std::string> lines;
    const ChildExit exit = runChild({"sh", "-c", "echo one >&2; printf 'two' >&2; exit 3"}, "",
                                    [&](const std::string& line) { lines.push_back(line); }, false);
    EXPECT_TRUE(exit.started);
    EXPECT_EQ(exit.status, 3);
    EXPECT_EQ(lines, (std::vector<std::string>{"one", "two"}));
    EXPECT_GT(exit.peakMemoryKB, 0);
    const ChildExit killed = runChild({"sh", "-c", "kill -9 $$"}, "", [](const std::string&) {}, false);
    EXPECT_EQ(killed.signal, SIGKILL);
    const ChildExit missing = runChild({"/nonexistent/hdhair-record"}, "", [](const std::string&) {}, false);
    EXPECT_FALSE(missing.started);
    EXPECT_NE(missing.startError.find("/nonexistent/hdhair-record"), std::string::npos);
    std::string out, err;
    const ChildExit captured = captureChild({"sh", "-c", "echo out; echo err >&2"}, out, err);
    EXPECT_EQ(captured.status, 0);
    EXPECT_EQ(out, "out\n");
    EXPECT_EQ(err, "err\n");
}

// A stand-in for hdhair-record that copies a complete image to the frame's
// output, except: frame 3 is an input error, frame 4 fails the machine once,
// frame 5 is killed every time.
TEST_F(FarmFolder, ATaskRetriesMachineFailuresAndRecordsEachFrame) {
    const std::string image = (folder / "template.exr").string();
    writeFrameImage(image, 4, 3);
    const std::string script = (folder / "fake-record.sh").string();
    std::ofstream(script) << "#!/bin/sh\n"
                             "while [ $# -gt 0 ]; do case \"$1\" in --frames) f=$2; shift;; esac; shift; done\n"
                             "case $f in\n"
                             "3) echo 'hdhair-record: error: /cam.focalLength: 0 is not a positive length' >&2; exit 1;;\n"
                             "4) if [ ! -e " + (folder / "once").string() + " ]; then touch " +
                                 (folder / "once").string() +
                             "; echo 'hdhair-record: error: out of memory' >&2; exit 75; fi;;\n"
                             "5) touch " + (folder / "out").string() + "/.frame.5.tmp-0a1b2c.exr; kill -9 $$;;\n"
                             "esac\n"
                             "cp " + image + " " + (folder / "out").string() + "/frame.$f.exr\n";
    fs::permissions(script, fs::perms::owner_all);
    FarmJob job = jobOf({1, 2, 3, 4, 5}, 5);
    std::ofstream(folder / "out" / ".frame.6.tmp-0a1b2c.exr") << "frame 6's";
    job.recordExecutable = script;
    job.retries = 2;
    writeFrameImage(job.outputOf(2), 4, 3);  // complete already: skipped

    const FrameTaskResult result = runFrameTask(job, 0, "41");
    EXPECT_EQ(result.rendered, 2);
    EXPECT_EQ(result.skipped, 1);
    EXPECT_EQ(result.failed, 2);
    const auto one = readFrameRecord(job, 1), two = readFrameRecord(job, 2), three = readFrameRecord(job, 3),
               four = readFrameRecord(job, 4), five = readFrameRecord(job, 5);
    ASSERT_TRUE(one && two && three && four && five);
    EXPECT_EQ(one->state, FrameState::Done);
    EXPECT_TRUE(one->rendered);
    EXPECT_EQ(two->state, FrameState::Done);
    EXPECT_FALSE(two->rendered);
    EXPECT_EQ(three->state, FrameState::Failed);
    EXPECT_EQ(three->attempts, 1);  // an input error is not retried
    EXPECT_TRUE(three->inputError);
    EXPECT_EQ(three->error, "/cam.focalLength: 0 is not a positive length");
    EXPECT_EQ(three->log, job.taskLog(0));
    EXPECT_EQ(four->state, FrameState::Done);
    EXPECT_EQ(four->attempts, 2);
    EXPECT_EQ(five->state, FrameState::Failed);
    EXPECT_EQ(five->attempts, 3);  // the first try and two retries
    EXPECT_NE(five->error.find("signal 9"), std::string::npos) << five->error;
    // The killed tries' hidden temporaries are gone; another file's are kept.
    EXPECT_FALSE(fs::exists(folder / "out" / ".frame.5.tmp-0a1b2c.exr"));
    EXPECT_TRUE(fs::exists(folder / "out" / ".frame.6.tmp-0a1b2c.exr"));
    EXPECT_EQ(whyFrameIncomplete(job.outputOf(4), 4, 3), "");

    // --force renders a complete frame again.
    job.force = true;
    job.framesToRender = {2};
    EXPECT_EQ(runFrameTask(job, 0, "42").rendered, 1);
}

}  // namespace
}  // namespace hdhair::farm
