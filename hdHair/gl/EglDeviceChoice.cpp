#include "hdHair/gl/EglDeviceChoice.h"

#include <algorithm>
#include <set>
#include <stdexcept>

namespace hdhair::gl {
namespace {

std::string trim(const std::string& text) {
    const size_t first = text.find_first_not_of(" \t\r\n");
    if (first == std::string::npos) return "";
    return text.substr(first, text.find_last_not_of(" \t\r\n") - first + 1);
}

// "2, 3" -> {"2", "3"}; "" -> {}.
std::vector<std::string> splitList(const std::string& value) {
    std::vector<std::string> entries;
    if (trim(value).empty()) return entries;
    size_t start = 0;
    for (;;) {
        const size_t comma = value.find(',', start);
        entries.push_back(trim(value.substr(start, comma == std::string::npos ? std::string::npos : comma - start)));
        if (comma == std::string::npos) return entries;
        start = comma + 1;
    }
}

// A non-negative integer of digits only: "-1", "+2", "0x1", "1.0" and
// "GPU-..." are none. Nine digits at most, so that it fits an int.
std::optional<int> parseIndex(const std::string& text) {
    if (text.empty() || text.size() > 9) return std::nullopt;
    if (!std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; })) return std::nullopt;
    return std::stoi(text);
}

// The first index of a list of non-negative integers; nothing when any entry
// is something else, since a list that is partly ids is no list Slurm wrote.
std::optional<int> firstIndexOfList(const std::string& value) {
    const std::vector<std::string> entries = splitList(value);
    if (entries.empty()) return std::nullopt;
    for (const std::string& entry : entries)
        if (!parseIndex(entry)) return std::nullopt;
    return parseIndex(entries.front());
}

// How many GPUs CUDA sees through CUDA_VISIBLE_DEVICES: its entries up to the
// first that names none (CUDA stops there), an entry being an index or a
// GPU or MIG UUID. "NoDevFiles" and "" make it none.
size_t gpusCudaSees(const std::string& value) {
    size_t count = 0;
    for (const std::string& entry : splitList(value)) {
        const bool names = parseIndex(entry) || entry.rfind("GPU-", 0) == 0 || entry.rfind("MIG-", 0) == 0;
        if (!names) break;
        ++count;
    }
    return count;
}

std::string join(const std::vector<std::string>& parts, const char* separator) {
    std::string joined;
    for (size_t i = 0; i < parts.size(); ++i) joined += (i ? separator : "") + parts[i];
    return joined;
}

using Getenv = std::function<const char*(const char*)>;

// The variable's value, or nothing when it is unset.
std::optional<std::string> variable(const Getenv& getenv, const char* name) {
    const char* value = getenv(name);
    if (!value) return std::nullopt;
    return std::string(value);
}

// Rule (a): the device HDHAIR_EGL_DEVICE names, nothing when it is unset or
// blank; throws when it names no hardware device.
std::optional<EglDeviceChoice> deviceChosenByHand(const std::vector<EglDeviceFacts>& devices,
                                                  const std::vector<const EglDeviceFacts*>& hardware,
                                                  const Getenv& getenv) {
    const std::optional<std::string> explicitDevice = variable(getenv, "HDHAIR_EGL_DEVICE");
    if (!explicitDevice || trim(*explicitDevice).empty()) return std::nullopt;
    const std::optional<int> index = parseIndex(trim(*explicitDevice));
    for (const EglDeviceFacts* device : hardware)
        if (index && device->index == *index)
            return EglDeviceChoice{{device->index},
                                   device->name + ": chosen by HDHAIR_EGL_DEVICE=" + trim(*explicitDevice)};
    std::vector<std::string> names;
    for (const EglDeviceFacts& device : devices) names.push_back(device.name);
    throw std::invalid_argument("HDHAIR_EGL_DEVICE=" + trim(*explicitDevice) +
                                " is not the index of a hardware EGL device; the EGL devices here: " +
                                (names.empty() ? std::string("none") : join(names, ", ")));
}

// The GPU the environment gave this process, as rule (b) reads it.
struct GpuRequest {
    std::vector<std::string> notes;  // what was set and ignored, for the reason
    std::optional<int> gpu;          // the GPU's index: Slurm's, else CUDA_VISIBLE_DEVICES's
    std::string asked;               // "the GPU Slurm gave this task (SLURM_STEP_GPUS=2)"; "" when none was
    size_t cudaSees = 0;             // gpusCudaSees(CUDA_VISIBLE_DEVICES), 0 when unset
    std::string cudaVisibleSetting;  // "CUDA_VISIBLE_DEVICES=<value>"
};

// Reads SLURM_STEP_GPUS, SLURM_JOB_GPUS and CUDA_VISIBLE_DEVICES.
GpuRequest readGpuRequest(const Getenv& getenv) {
    // Slurm's global index first: it names the same GPU whether the job's
    // cgroup hides the others or not, where CUDA_VISIBLE_DEVICES may be
    // relative, UUIDs or "NoDevFiles".
    GpuRequest request;
    for (const char* name : {"SLURM_STEP_GPUS", "SLURM_JOB_GPUS"}) {
        const std::optional<std::string> value = variable(getenv, name);
        if (!value || trim(*value).empty()) continue;
        if ((request.gpu = firstIndexOfList(*value))) {
            request.asked = "the GPU Slurm gave this task (" + std::string(name) + "=" + *value + ")";
            break;
        }
        request.notes.push_back(std::string(name) + "=" + *value + " is no list of GPU indices, ignored");
    }
    const std::optional<std::string> cudaVisible = variable(getenv, "CUDA_VISIBLE_DEVICES");
    request.cudaSees = cudaVisible ? gpusCudaSees(*cudaVisible) : 0;
    request.cudaVisibleSetting = "CUDA_VISIBLE_DEVICES=" + cudaVisible.value_or("");
    if (request.asked.empty() && cudaVisible) {
        request.gpu = firstIndexOfList(*cudaVisible);
        // UUIDs name a GPU too, but only through CUDA's ordinals below.
        if (request.gpu || request.cudaSees > 0) request.asked = "the first GPU of " + request.cudaVisibleSetting;
        else request.notes.push_back(request.cudaVisibleSetting + " names no GPU, ignored");
    }
    return request;
}

// Every hardware device, the notes as the reason.
EglDeviceChoice everyHardwareDevice(const std::vector<const EglDeviceFacts*>& hardware,
                                    const std::vector<std::string>& notes) {
    EglDeviceChoice choice;
    for (const EglDeviceFacts* device : hardware) choice.hardwareOrder.push_back(device->index);
    choice.reason = join(notes, "; ");
    return choice;
}

// `line`, followed by the request's notes.
std::string withNotes(const GpuRequest& request, const std::string& line) {
    return request.notes.empty() ? line : line + "; " + join(request.notes, "; ");
}

// `device` alone, found as the requested GPU `how`.
EglDeviceChoice chooseDevice(const GpuRequest& request, const EglDeviceFacts& device, const std::string& how) {
    return EglDeviceChoice{{device.index}, withNotes(request, device.name + ": " + request.asked + ", " + how)};
}

// Not found: no hardware device at all rather than another task's GPU.
EglDeviceChoice missingDevice(const GpuRequest& request, const std::string& how, const std::string& found) {
    return EglDeviceChoice{{}, withNotes(request, request.asked + " would be " + how + ", which no EGL device is (" +
                                                      found +
                                                      "); no other GPU is tried, so as not to take another task's")};
}

// The CUDA ordinals the hardware devices report, empty when two devices
// claim one (then noted) and CUDA's ordinals cannot tie EGL devices to GPUs.
std::set<int> trustedCudaOrdinals(const std::vector<const EglDeviceFacts*>& hardware, GpuRequest& request) {
    std::set<int> reported;
    bool repeated = false;
    for (const EglDeviceFacts* device : hardware)
        if (device->cudaDevice) repeated |= !reported.insert(*device->cudaDevice).second;
    if (!repeated) return reported;
    request.notes.push_back("EGL devices report the same CUDA device twice, so CUDA devices are not used");
    return {};
}

// The device whose CUDA ordinal is the requested GPU's; `largestOrdinal` is
// the largest one the devices report.
EglDeviceChoice chooseByCudaDevice(const std::vector<const EglDeviceFacts*>& hardware, GpuRequest& request,
                                   int largestOrdinal) {
    std::optional<int> ordinal;
    std::string how;
    // Ordinals counted through CUDA_VISIBLE_DEVICES end below its length;
    // then its first GPU, the task's, is CUDA device 0. An ordinal past
    // it means the driver counts the machine's GPUs.
    if (request.cudaSees > 0 && static_cast<size_t>(largestOrdinal) < request.cudaSees) {
        ordinal = 0;
        how = "CUDA device 0 through " + request.cudaVisibleSetting;
    } else if (request.gpu) {
        ordinal = request.gpu;
        how = "CUDA device " + std::to_string(*request.gpu);
        if (request.cudaSees > 0) how += " (EGL counts CUDA devices past " + request.cudaVisibleSetting + ")";
    }
    if (ordinal) {
        std::vector<std::string> found;
        for (const EglDeviceFacts* device : hardware) {
            if (device->cudaDevice == ordinal) return chooseDevice(request, *device, how);
            found.push_back(device->name + (device->cudaDevice
                                                ? " is CUDA device " + std::to_string(*device->cudaDevice)
                                                : std::string(" has no CUDA device")));
        }
        return missingDevice(request, how, join(found, ", "));
    }
    // UUIDs in CUDA_VISIBLE_DEVICES while EGL counts the machine's GPUs:
    // nothing says which of them the UUID is.
    request.notes.push_back(request.cudaVisibleSetting + " names no GPU index, ignored");
    return everyHardwareDevice(hardware, request.notes);
}

// No CUDA devices (Mesa's drivers, or an NVIDIA driver without
// EGL_NV_device_cuda): the GPU's index counted among the hardware devices,
// which both Slurm and EGL order by the devices' place on the bus.
EglDeviceChoice chooseByHardwareIndex(const std::vector<const EglDeviceFacts*>& hardware, GpuRequest& request) {
    if (!request.gpu) {
        request.notes.push_back(request.cudaVisibleSetting +
                                " names no GPU index and no EGL device reports its CUDA device, ignored");
        return everyHardwareDevice(hardware, request.notes);
    }
    const int gpu = *request.gpu;
    const std::string how =
        "hardware EGL device #" + std::to_string(gpu) + " counted from 0 (no EGL device reports its CUDA device)";
    if (static_cast<size_t>(gpu) < hardware.size()) return chooseDevice(request, *hardware[gpu], how);
    std::vector<std::string> found;
    for (const EglDeviceFacts* device : hardware) found.push_back(device->name);
    const bool one = hardware.size() == 1;
    return missingDevice(request, how,
                         std::string(one ? "there is " : "there are ") + std::to_string(hardware.size()) +
                             " hardware EGL device" + (one ? "" : "s") +
                             (found.empty() ? "" : ": " + join(found, ", ")));
}

}  // namespace

EglDeviceChoice chooseEglDevices(const std::vector<EglDeviceFacts>& devices,
                                 const std::function<const char*(const char*)>& getenv) {
    std::vector<const EglDeviceFacts*> hardware;
    for (const EglDeviceFacts& device : devices)
        if (device.hardware) hardware.push_back(&device);

    // (a) A device named by hand: that one or an error, never another one.
    if (std::optional<EglDeviceChoice> chosen = deviceChosenByHand(devices, hardware, getenv)) return *chosen;

    // (b) The GPU this process was given.
    GpuRequest request = readGpuRequest(getenv);
    // (c) Nothing asked for: every hardware device, as before.
    if (request.asked.empty()) return everyHardwareDevice(hardware, request.notes);

    // CUDA's ordinals tie EGL devices to GPUs, unless two devices claim one.
    const std::set<int> ordinals = trustedCudaOrdinals(hardware, request);
    if (!ordinals.empty()) return chooseByCudaDevice(hardware, request, *ordinals.rbegin());
    return chooseByHardwareIndex(hardware, request);
}

}  // namespace hdhair::gl
