// openImageBandReader for the Hydra plugin (ImageBandReader.h): OpenImageIO
// lives in hdHairImageReader.so, beside the library this code is linked
// into, and is loaded on the first call only.

#include <dlfcn.h>

#include <mutex>

#include "hdHair/environment/ImageBandReader.h"

namespace hdhair {

namespace {

using OpenFunction = ImageBandReader* (*)(const char*, std::string*);

struct LoadedModule {
    OpenFunction open = nullptr;
    std::string problem;  // why it could not be loaded ("" when it was)
};

// The module's file: beside the shared object that holds this function
// (plugin/usd/hdHair.so in the build and install trees alike).
std::string modulePath() {
    Dl_info info{};
    const std::string name = "hdHairImageReader.so";
    if (!dladdr(reinterpret_cast<void*>(&modulePath), &info) || !info.dli_fname) return name;
    const std::string self = info.dli_fname;
    const size_t slash = self.rfind('/');
    return slash == std::string::npos ? name : self.substr(0, slash + 1) + name;
}

const LoadedModule& loadedModule() {
    static LoadedModule module;
    static std::once_flag once;
    std::call_once(once, [] {
        const std::string path = modulePath();
        // Never closed: readers it made may outlive any one caller.
        void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
            const char* error = dlerror();
            module.problem = "hdHair's image reader could not be loaded (" + std::string(error ? error : path) + ")";
            return;
        }
        module.open = reinterpret_cast<OpenFunction>(dlsym(handle, "hdhairOpenImageBandReader"));
        if (!module.open) module.problem = "hdHair's image reader " + path + " has no hdhairOpenImageBandReader";
    });
    return module;
}

}  // namespace

std::unique_ptr<ImageBandReader> openImageBandReader(const std::string& path, std::string& why) {
    const LoadedModule& module = loadedModule();
    if (!module.open) {
        why = module.problem;
        return nullptr;
    }
    return std::unique_ptr<ImageBandReader>(module.open(path.c_str(), &why));
}

}  // namespace hdhair
