// Which hardware EGL devices a context is tried on (hdHair/gl/EglDeviceChoice.h):
// every one by default, the one named by HDHAIR_EGL_DEVICE, and on a Slurm
// farm only the GPU the task was given, found through EGL_NV_device_cuda's
// CUDA ordinals or, without them, by its place among the hardware devices.
// Made-up device lists and environments: no EGL call, no GPU needed.

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hdHair/gl/EglDeviceChoice.h"

using namespace hdhair::gl;

namespace {

using Environment = std::map<std::string, std::string>;

EglDeviceChoice choose(const std::vector<EglDeviceFacts>& devices, const Environment& environment) {
    return chooseEglDevices(devices, [&](const char* name) -> const char* {
        auto found = environment.find(name);
        return found == environment.end() ? nullptr : found->second.c_str();
    });
}

EglDeviceFacts nvidia(int index, std::optional<int> cudaDevice) {
    return {index, true, cudaDevice, "EGL device " + std::to_string(index) + " (NVIDIA H200)"};
}

EglDeviceFacts mesaGpu(int index) {
    return {index, true, std::nullopt, "EGL device " + std::to_string(index) + " (/dev/dri/renderD" +
                                           std::to_string(128 + index) + ")"};
}

EglDeviceFacts software(int index) {
    return {index, false, std::nullopt, "EGL device " + std::to_string(index) + " (software)"};
}

bool mentions(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Four NVIDIA GPUs enumerated out of CUDA's order, then Mesa's software
// device, as a whole node looks to a process that sees every GPU.
const std::vector<EglDeviceFacts> wholeNode = {nvidia(0, 2), nvidia(1, 3), nvidia(2, 1), nvidia(3, 0), software(4)};
// The same node without EGL_NV_device_cuda (or Mesa's drivers): no ordinals,
// and the software device enumerated first so that counting must skip it.
const std::vector<EglDeviceFacts> noOrdinals = {software(0), mesaGpu(1), mesaGpu(2), mesaGpu(3)};

}  // namespace

TEST(EglDeviceChoice, WithoutSlurmEveryHardwareDeviceInEnumerationOrder) {
    const EglDeviceChoice choice = choose(wholeNode, {});
    EXPECT_EQ(choice.hardwareOrder, (std::vector<int>{0, 1, 2, 3}));
    EXPECT_EQ(choice.reason, "");
    EXPECT_EQ(choose(noOrdinals, {}).hardwareOrder, (std::vector<int>{1, 2, 3}));
}

TEST(EglDeviceChoice, SlurmStepGpuIsTheDeviceOfThatCudaOrdinalWhereverItIsEnumerated) {
    // CUDA_VISIBLE_DEVICES unset: the ordinals are the machine's.
    const EglDeviceChoice choice = choose(wholeNode, {{"SLURM_STEP_GPUS", "1"}});
    EXPECT_EQ(choice.hardwareOrder, std::vector<int>{2});
    EXPECT_EQ(choice.reason.rfind("EGL device 2 (NVIDIA H200): ", 0), 0u) << choice.reason;
    EXPECT_TRUE(mentions(choice.reason, "SLURM_STEP_GPUS=1")) << choice.reason;
    EXPECT_TRUE(mentions(choice.reason, "CUDA device 1")) << choice.reason;
}

TEST(EglDeviceChoice, SlurmJobGpusServeWhenThereIsNoStep) {
    const EglDeviceChoice choice = choose(wholeNode, {{"SLURM_JOB_GPUS", "3"}});
    EXPECT_EQ(choice.hardwareOrder, std::vector<int>{1});
    EXPECT_TRUE(mentions(choice.reason, "SLURM_JOB_GPUS=3")) << choice.reason;
}

TEST(EglDeviceChoice, TheStepsGpuWinsOverTheJobs) {
    const EglDeviceChoice choice = choose(wholeNode, {{"SLURM_STEP_GPUS", "0"}, {"SLURM_JOB_GPUS", "0,1,2,3"}});
    EXPECT_EQ(choice.hardwareOrder, std::vector<int>{3});
    EXPECT_TRUE(mentions(choice.reason, "SLURM_STEP_GPUS=0")) << choice.reason;
}

TEST(EglDeviceChoice, ATaskGivenSeveralGpusRendersOnItsFirst) {
    EXPECT_EQ(choose(wholeNode, {{"SLURM_STEP_GPUS", "2,3"}}).hardwareOrder, std::vector<int>{0});
    EXPECT_EQ(choose(noOrdinals, {{"SLURM_JOB_GPUS", "2,3"}}).hardwareOrder, std::vector<int>{3});
}

TEST(EglDeviceChoice, CudaVisibleDevicesIndicesServeWithoutSlurm) {
    // Ordinals counted past the list (the machine's): the listed index itself.
    EXPECT_EQ(choose(wholeNode, {{"CUDA_VISIBLE_DEVICES", "3,1"}}).hardwareOrder, std::vector<int>{1});
    EXPECT_EQ(choose(noOrdinals, {{"CUDA_VISIBLE_DEVICES", "1"}}).hardwareOrder, std::vector<int>{2});
}

TEST(EglDeviceChoice, CudaVisibleDevicesUuidsAreIgnoredWhenNothingTiesThemToADevice) {
    for (const auto& devices : {wholeNode, noOrdinals}) {
        const EglDeviceChoice choice = choose(devices, {{"CUDA_VISIBLE_DEVICES", "GPU-abc"}});
        EXPECT_EQ(choice.hardwareOrder, choose(devices, {}).hardwareOrder);
        EXPECT_TRUE(mentions(choice.reason, "CUDA_VISIBLE_DEVICES=GPU-abc")) << choice.reason;
        EXPECT_TRUE(mentions(choice.reason, "ignored")) << choice.reason;
    }
}

TEST(EglDeviceChoice, NoDevFilesAndAnEmptyListAreIgnored) {
    for (const char* value : {"NoDevFiles", ""}) {
        const EglDeviceChoice choice = choose(wholeNode, {{"CUDA_VISIBLE_DEVICES", value}});
        EXPECT_EQ(choice.hardwareOrder, (std::vector<int>{0, 1, 2, 3})) << value;
        EXPECT_TRUE(mentions(choice.reason, std::string("CUDA_VISIBLE_DEVICES=") + value + " names no GPU, ignored"))
            << choice.reason;
    }
    // Beside Slurm's index it is no obstacle.
    EXPECT_EQ(choose(wholeNode, {{"SLURM_JOB_GPUS", "1"}, {"CUDA_VISIBLE_DEVICES", "NoDevFiles"}}).hardwareOrder,
              std::vector<int>{2});
}

TEST(EglDeviceChoice, AMalformedSlurmListIsIgnoredAndSaidSo) {
    const EglDeviceChoice choice = choose(wholeNode, {{"SLURM_STEP_GPUS", "gpu:2"}, {"SLURM_JOB_GPUS", "0"}});
    EXPECT_EQ(choice.hardwareOrder, std::vector<int>{3});
    EXPECT_TRUE(mentions(choice.reason, "SLURM_STEP_GPUS=gpu:2 is no list of GPU indices, ignored")) << choice.reason;
}

// Where devices report CUDA ordinals counted through CUDA_VISIBLE_DEVICES,
// the task's GPU is CUDA device 0 whatever Slurm's global index is.
TEST(EglDeviceChoice, UnderADeviceCgroupTheTasksOnlyGpuIsCudaDeviceZero) {
    // ConstrainDevices: the process opens only GPU 2 of the node, which CUDA
    // and CUDA_VISIBLE_DEVICES call 0.
    const std::vector<EglDeviceFacts> constrained = {nvidia(0, 0), software(1)};
    const EglDeviceChoice choice =
        choose(constrained, {{"SLURM_STEP_GPUS", "2"}, {"CUDA_VISIBLE_DEVICES", "0"}});
    EXPECT_EQ(choice.hardwareOrder, std::vector<int>{0});
    EXPECT_TRUE(mentions(choice.reason, "SLURM_STEP_GPUS=2")) << choice.reason;
    EXPECT_TRUE(mentions(choice.reason, "CUDA device 0 through CUDA_VISIBLE_DEVICES=0")) << choice.reason;
}

TEST(EglDeviceChoice, WithoutACgroupTheListedGpuIsStillCudaDeviceZero) {
    // Every GPU enumerated; CUDA_VISIBLE_DEVICES=2 leaves the others without
    // an ordinal, and makes GPU 2 (here EGL device 1) CUDA device 0.
    const std::vector<EglDeviceFacts> node = {nvidia(0, std::nullopt), nvidia(1, 0), nvidia(2, std::nullopt),
                                              nvidia(3, std::nullopt)};
    EXPECT_EQ(choose(node, {{"SLURM_STEP_GPUS", "2"}, {"CUDA_VISIBLE_DEVICES", "2"}}).hardwareOrder,
              std::vector<int>{1});
    // UUIDs work the same way.
    EXPECT_EQ(choose(node, {{"CUDA_VISIBLE_DEVICES", "GPU-8932f937"}}).hardwareOrder, std::vector<int>{1});
}

TEST(EglDeviceChoice, OrdinalsPastCudaVisibleDevicesAreTheMachinesAndMatchSlurmsIndex) {
    // A driver that reports every GPU's machine ordinal despite
    // CUDA_VISIBLE_DEVICES=1: CUDA device 0 would be another task's GPU.
    const EglDeviceChoice choice = choose(wholeNode, {{"SLURM_STEP_GPUS", "1"}, {"CUDA_VISIBLE_DEVICES", "1"}});
    EXPECT_EQ(choice.hardwareOrder, std::vector<int>{2});
    EXPECT_TRUE(mentions(choice.reason, "past CUDA_VISIBLE_DEVICES=1")) << choice.reason;
}

TEST(EglDeviceChoice, WithoutOrdinalsTheGpuIsCountedAmongHardwareDevicesOnly) {
    // GPU 0 is the first hardware device, EGL device 1: the software device
    // enumerated before it is not counted.
    const EglDeviceChoice choice = choose(noOrdinals, {{"SLURM_STEP_GPUS", "0"}});
    EXPECT_EQ(choice.hardwareOrder, std::vector<int>{1});
    EXPECT_EQ(choice.reason.rfind("EGL device 1 (/dev/dri/renderD129): ", 0), 0u) << choice.reason;
    EXPECT_TRUE(mentions(choice.reason, "no EGL device reports its CUDA device")) << choice.reason;
}

TEST(EglDeviceChoice, OrdinalsTwoDevicesClaimAreNotTrusted) {
    const std::vector<EglDeviceFacts> confused = {nvidia(0, 0), nvidia(1, 0), nvidia(2, 0)};
    const EglDeviceChoice choice = choose(confused, {{"SLURM_STEP_GPUS", "2"}, {"CUDA_VISIBLE_DEVICES", "0"}});
    EXPECT_EQ(choice.hardwareOrder, std::vector<int>{2});  // counted, not matched
    EXPECT_TRUE(mentions(choice.reason, "same CUDA device twice")) << choice.reason;
}

TEST(EglDeviceChoice, AGpuThatIsNotThereLeavesNoHardwareDeviceAndSaysWhich) {
    const EglDeviceChoice byOrdinal = choose(wholeNode, {{"SLURM_STEP_GPUS", "7"}});
    EXPECT_TRUE(byOrdinal.hardwareOrder.empty());
    EXPECT_TRUE(mentions(byOrdinal.reason, "SLURM_STEP_GPUS=7")) << byOrdinal.reason;
    EXPECT_TRUE(mentions(byOrdinal.reason, "CUDA device 7")) << byOrdinal.reason;
    EXPECT_TRUE(mentions(byOrdinal.reason, "EGL device 3 (NVIDIA H200) is CUDA device 0")) << byOrdinal.reason;

    const EglDeviceChoice counted = choose(noOrdinals, {{"SLURM_JOB_GPUS", "3"}});
    EXPECT_TRUE(counted.hardwareOrder.empty());
    EXPECT_TRUE(mentions(counted.reason, "SLURM_JOB_GPUS=3")) << counted.reason;
    EXPECT_TRUE(mentions(counted.reason, "there are 3 hardware EGL devices")) << counted.reason;
    EXPECT_EQ(counted.reason.find('\n'), std::string::npos);
}

TEST(EglDeviceChoice, HdhairEglDeviceNamesTheDeviceAndOutranksSlurm) {
    const EglDeviceChoice choice = choose(wholeNode, {{"HDHAIR_EGL_DEVICE", "3"}, {"SLURM_STEP_GPUS", "1"}});
    EXPECT_EQ(choice.hardwareOrder, std::vector<int>{3});
    EXPECT_EQ(choice.reason, "EGL device 3 (NVIDIA H200): chosen by HDHAIR_EGL_DEVICE=3");
    // An empty value is no choice.
    EXPECT_EQ(choose(wholeNode, {{"HDHAIR_EGL_DEVICE", ""}}).hardwareOrder, (std::vector<int>{0, 1, 2, 3}));
}

TEST(EglDeviceChoice, AnHdhairEglDeviceThatIsNoHardwareDeviceThrowsOneLine) {
    // Out of range, the software device, and no index at all.
    for (const char* value : {"9", "4", "first", "-1"}) {
        try {
            choose(wholeNode, {{"HDHAIR_EGL_DEVICE", value}});
            ADD_FAILURE() << "HDHAIR_EGL_DEVICE=" << value << " was accepted";
        } catch (const std::invalid_argument& error) {
            const std::string message = error.what();
            EXPECT_EQ(message.rfind(std::string("HDHAIR_EGL_DEVICE=") + value + " ", 0), 0u) << message;
            EXPECT_TRUE(mentions(message, "EGL device 4 (software)")) << message;
            EXPECT_TRUE(mentions(message, "EGL device 0 (NVIDIA H200)")) << message;
            EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        }
    }
}

TEST(EglDeviceChoice, ASoftwareOnlyMachineHasNoHardwareDeviceToTry) {
    const std::vector<EglDeviceFacts> ci = {software(0)};
    const EglDeviceChoice plain = choose(ci, {});
    EXPECT_TRUE(plain.hardwareOrder.empty());
    EXPECT_EQ(plain.reason, "");
    const EglDeviceChoice slurm = choose(ci, {{"SLURM_JOB_GPUS", "0"}});
    EXPECT_TRUE(slurm.hardwareOrder.empty());
    EXPECT_TRUE(mentions(slurm.reason, "SLURM_JOB_GPUS=0")) << slurm.reason;
    EXPECT_TRUE(mentions(slurm.reason, "there are 0 hardware EGL devices")) << slurm.reason;
    EXPECT_THROW(choose(ci, {{"HDHAIR_EGL_DEVICE", "0"}}), std::invalid_argument);
}
