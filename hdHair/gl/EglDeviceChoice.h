#pragma once
// Which hardware EGL devices a headless context may be made on. On a machine
// with several GPUs EGL enumerates them all, and EglContext used to take the
// first that worked: EGL device 0. On a Slurm farm every array task that was
// given its own GPU then rendered on the same one, next to (and out of memory
// beside) the other tasks, while the GPUs it was given sat idle. These are
// the decisions that pick the task's own GPU, kept free of EGL calls so that
// they can be tested with a made-up device list and environment.
//
// Slurm's GRES: a job or step given GPUs (--gres=gpu:N, --gpus...) gets
//  - SLURM_STEP_GPUS (in a step, srun) and SLURM_JOB_GPUS (in the batch
//    script): the GPUs' global indices as gres.conf numbers them ("2",
//    "2,3"), whatever the job's device cgroup lets it see;
//  - CUDA_VISIBLE_DEVICES: the same GPUs as the process's CUDA sees them:
//    relative ("0") when the device cgroup (ConstrainDevices=yes) hides the
//    others, so that the job's one GPU is the only one there is, global ("2")
//    when it does not; UUIDs ("GPU-8932f937-...") where a site configures
//    that, and "NoDevFiles" when gres.conf gives the GPUs no device files.
// So the global index is the one that names the same GPU everywhere, and
// CUDA_VISIBLE_DEVICES alone cannot tell "0 of the GPUs I can see" from
// "GPU 0 of the machine".
//
// EGL numbers its devices its own way: NVIDIA's driver enumerates the GPUs a
// process can open, then Mesa's devices (DRM devices, its software device)
// follow, so an EGL index says nothing of Slurm's. What ties an EGL device to
// a GPU is EGL_NV_device_cuda: EGL_CUDA_DEVICE_NV is the device's CUDA
// device enumerant, which is an ordinal of this process's CUDA, that is
// counted through CUDA_VISIBLE_DEVICES: with CUDA_VISIBLE_DEVICES set, CUDA
// device 0 is the first GPU it lists, which is the task's first GPU whether
// the list is relative, global or UUIDs, and the GPUs it leaves out have no
// ordinal to report (drivers that reported one ordinal for several devices
// are not trusted: two devices claiming one ordinal leave ordinals unused).
// Matching Slurm's global index against these ordinals would miss in both
// cgroup set-ups. Without CUDA_VISIBLE_DEVICES the ordinals are the
// machine's own and the global index is matched directly (CUDA's default
// order, fastest first, is PCI order on a node of one GPU model; set
// CUDA_DEVICE_ORDER=PCI_BUS_ID on a mixed one). A driver that counted past
// CUDA_VISIBLE_DEVICES (a device reporting an ordinal the list cannot have)
// is read the second way, so neither reading hangs on one driver's habit.

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace hdhair::gl {

// What EglContext knows of one enumerated EGL device.
struct EglDeviceFacts {
    int index = 0;          // its position in eglQueryDevicesEXT's list
    bool hardware = false;  // not Mesa's software device (SoftwareRenderer.h)
    // EGL_CUDA_DEVICE_NV, where the device has EGL_NV_device_cuda and the
    // query succeeds: this process's CUDA ordinal of the GPU.
    std::optional<int> cudaDevice;
    // Its description, index included: "EGL device 2 (NVIDIA H200, /dev/dri/renderD130)".
    std::string name;
};

struct EglDeviceChoice {
    // The indices of the hardware devices to try, in order. Empty when there
    // are none, or when the GPU this process was given is not among them:
    // the caller then goes on to Mesa's platforms and its software warning
    // says why, rather than take another task's GPU.
    std::vector<int> hardwareOrder;
    // One line for --verbose and for errors, "" when nothing in the
    // environment asked for a GPU. When one device is chosen it begins with
    // that device's name: "EGL device 2 (NVIDIA H200): the GPU Slurm gave
    // this task (SLURM_STEP_GPUS=2), CUDA device 0 through CUDA_VISIBLE_DEVICES=0".
    std::string reason;
};

// The hardware devices to try, by these rules in order:
//  (a) HDHAIR_EGL_DEVICE=N, an EGL device index: only that device. An index
//      that is no hardware device here (or no index) throws
//      std::invalid_argument, one line naming the variable, its value and the
//      devices there are: a device asked for by hand is not silently replaced.
//  (b) the first GPU of SLURM_STEP_GPUS, else of SLURM_JOB_GPUS, else of
//      CUDA_VISIBLE_DEVICES: only the device that is that GPU. With CUDA
//      devices reported (and no two devices reporting the same one), the
//      device whose CUDA device is that GPU's ordinal (see above); else the
//      GPU's index counted among the hardware devices in enumeration order.
//      A value that is not a list of non-negative integers ("NoDevFiles",
//      "", a malformed Slurm list) is ignored and the reason says so; UUIDs
//      in CUDA_VISIBLE_DEVICES still name its first GPU as CUDA device 0
//      where devices report ordinals counted through it, and are ignored
//      otherwise. A task given several GPUs renders on its first.
//  (c) otherwise every hardware device in enumeration order.
// getenv is std::getenv in EglContext, a map in the tests.
EglDeviceChoice chooseEglDevices(const std::vector<EglDeviceFacts>& devices,
                                 const std::function<const char*(const char*)>& getenv);

}  // namespace hdhair::gl
