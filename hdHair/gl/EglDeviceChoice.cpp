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

}  // namespace

EglDeviceChoice chooseEglDevices(const std::vector<EglDeviceFacts>& devices,
                                 const std::function<const char*(const char*)>& getenv) {
    auto variable = [&](const char* name) -> std::optional<std::string> {
        const char* value = getenv(name);
        if (!value) return std::nullopt;
        return std::string(value);
    };
    std::vector<const EglDeviceFacts*> hardware;
    for (const EglDeviceFacts& device : devices)
        if (device.hardware) hardware.push_back(&device);

    // (a) A device named by hand: that one or an error, never another one.
    if (const std::optional<std::string> explicitDevice = variable("HDHAIR_EGL_DEVICE");
        explicitDevice && !trim(*explicitDevice).empty()) {
        const std::optional<int> index = parseIndex(trim(*explicitDevice));
        for (const EglDeviceFacts* device : hardware)
            if (index && device->index == *index)
                return {{device->index}, device->name + ": chosen by HDHAIR_EGL_DEVICE=" + trim(*explicitDevice)};
        std::vector<std::string> names;
        for (const EglDeviceFacts& device : devices) names.push_back(device.name);
        throw std::invalid_argument("HDHAIR_EGL_DEVICE=" + trim(*explicitDevice) +
                                    " is not the index of a hardware EGL device; the EGL devices here: " +
                                    (names.empty() ? std::string("none") : join(names, ", ")));
    }

    // (b) The GPU this process was given. Slurm's global index first: it
    // names the same GPU whether the job's cgroup hides the others or not,
    // where CUDA_VISIBLE_DEVICES may be relative, UUIDs or "NoDevFiles".
    std::vector<std::string> notes;  // what was set and ignored, for the reason
    std::optional<int> gpu;          // the GPU's index: Slurm's, else CUDA_VISIBLE_DEVICES's
    std::string asked;               // "the GPU Slurm gave this task (SLURM_STEP_GPUS=2)"
    for (const char* name : {"SLURM_STEP_GPUS", "SLURM_JOB_GPUS"}) {
        const std::optional<std::string> value = variable(name);
        if (!value || trim(*value).empty()) continue;
        if ((gpu = firstIndexOfList(*value))) {
            asked = "the GPU Slurm gave this task (" + std::string(name) + "=" + *value + ")";
            break;
        }
        notes.push_back(std::string(name) + "=" + *value + " is no list of GPU indices, ignored");
    }
    const std::optional<std::string> cudaVisible = variable("CUDA_VISIBLE_DEVICES");
    const size_t cudaSees = cudaVisible ? gpusCudaSees(*cudaVisible) : 0;
    const std::string cudaVisibleSetting = "CUDA_VISIBLE_DEVICES=" + cudaVisible.value_or("");
    if (asked.empty() && cudaVisible) {
        gpu = firstIndexOfList(*cudaVisible);
        // UUIDs name a GPU too, but only through CUDA's ordinals below.
        if (gpu || cudaSees > 0) asked = "the first GPU of " + cudaVisibleSetting;
        else notes.push_back(cudaVisibleSetting + " names no GPU, ignored");
    }
    auto everyHardwareDevice = [&] {
        EglDeviceChoice choice;
        for (const EglDeviceFacts* device : hardware) choice.hardwareOrder.push_back(device->index);
        choice.reason = join(notes, "; ");
        return choice;
    };
    // (c) Nothing asked for: every hardware device, as before.
    if (asked.empty()) return everyHardwareDevice();
    auto reason = [&](const std::string& line) { return notes.empty() ? line : line + "; " + join(notes, "; "); };
    auto choose = [&](const EglDeviceFacts& device, const std::string& how) {
        return EglDeviceChoice{{device.index}, reason(device.name + ": " + asked + ", " + how)};
    };
    // Not found: no hardware device at all rather than another task's GPU.
    auto missing = [&](const std::string& how, const std::string& found) {
        return EglDeviceChoice{{}, reason(asked + " would be " + how + ", which no EGL device is (" + found +
                                          "); no other GPU is tried, so as not to take another task's")};
    };

    // CUDA's ordinals tie EGL devices to GPUs, unless two devices claim one.
    std::set<int> reported;
    bool repeated = false;
    for (const EglDeviceFacts* device : hardware)
        if (device->cudaDevice) repeated |= !reported.insert(*device->cudaDevice).second;
    if (repeated) notes.push_back("EGL devices report the same CUDA device twice, so CUDA devices are not used");
    if (!reported.empty() && !repeated) {
        std::optional<int> ordinal;
        std::string how;
        // Ordinals counted through CUDA_VISIBLE_DEVICES end below its length;
        // then its first GPU, the task's, is CUDA device 0. An ordinal past
        // it means the driver counts the machine's GPUs.
        if (cudaSees > 0 && static_cast<size_t>(*reported.rbegin()) < cudaSees) {
            ordinal = 0;
            how = "CUDA device 0 through " + cudaVisibleSetting;
        } else if (gpu) {
            ordinal = gpu;
            how = "CUDA device " + std::to_string(*gpu);
            if (cudaSees > 0) how += " (EGL counts CUDA devices past " + cudaVisibleSetting + ")";
        }
        if (ordinal) {
            std::vector<std::string> found;
            for (const EglDeviceFacts* device : hardware) {
                if (device->cudaDevice == ordinal) return choose(*device, how);
                found.push_back(device->name + (device->cudaDevice
                                                    ? " is CUDA device " + std::to_string(*device->cudaDevice)
                                                    : std::string(" has no CUDA device")));
            }
            return missing(how, join(found, ", "));
        }
        // UUIDs in CUDA_VISIBLE_DEVICES while EGL counts the machine's GPUs:
        // nothing says which of them the UUID is.
        notes.push_back(cudaVisibleSetting + " names no GPU index, ignored");
        return everyHardwareDevice();
    }

    // No CUDA devices (Mesa's drivers, or an NVIDIA driver without
    // EGL_NV_device_cuda): the GPU's index counted among the hardware devices,
    // which both Slurm and EGL order by the devices' place on the bus.
    if (!gpu) {
        notes.push_back(cudaVisibleSetting + " names no GPU index and no EGL device reports its CUDA device, ignored");
        return everyHardwareDevice();
    }
    const std::string how = "hardware EGL device #" + std::to_string(*gpu) +
                            " counted from 0 (no EGL device reports its CUDA device)";
    if (static_cast<size_t>(*gpu) < hardware.size()) return choose(*hardware[*gpu], how);
    std::vector<std::string> found;
    for (const EglDeviceFacts* device : hardware) found.push_back(device->name);
    const bool one = hardware.size() == 1;
    return missing(how, std::string(one ? "there is " : "there are ") + std::to_string(hardware.size()) +
                            " hardware EGL device" + (one ? "" : "s") + (found.empty() ? "" : ": " + join(found, ", ")));
}

}  // namespace hdhair::gl
