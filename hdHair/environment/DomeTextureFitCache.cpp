#include "hdHair/environment/DomeTextureFitCache.h"

#include <chrono>
#include <exception>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "hdHair/base/InputError.h"
#include "hdHair/base/RegularFile.h"
#include "hdHair/environment/LatlongTexture.h"

namespace hdhair {

namespace {

// The largest grid a fit uses: 1024 × 512 cells are 0.35°, far finer than
// the narrowest lobe, and the fit's cost grows with the cell count.
constexpr int kMaxGridWidth = 1024;
constexpr int kMaxGridHeight = 512;

std::shared_ptr<const DomeTextureFit> failure(const std::string& path, const std::string& why) {
    auto fit = std::make_shared<DomeTextureFit>();
    fit->error = "cannot read '" + path + "': " + why;
    return fit;
}

std::shared_ptr<const DomeTextureFit> readAndFit(const std::string& path, const DomeFitSettings& settings) {
    auto fit = std::make_shared<DomeTextureFit>();
    try {
        LatlongTextureRead read = readLatlongTexture(path, settings.gridWidth, settings.gridHeight);
        fit->fit = fitSrbfs(read.grid, settings.srbf);
        fit->imageWidth = read.imageWidth;
        fit->imageHeight = read.imageHeight;
        fit->repairedTexels = read.repairedTexels;
    } catch (const InputError& error) {
        fit->error = error.what();
    }
    return fit;
}

}  // namespace

DomeTextureFitCache& DomeTextureFitCache::process() {
    static DomeTextureFitCache cache;
    return cache;
}

std::shared_ptr<const DomeTextureFit> DomeTextureFitCache::latlongFit(const std::string& path,
                                                                      const DomeFitSettings& settings) {
    if (settings.gridWidth < 1 || settings.gridWidth > kMaxGridWidth || settings.gridHeight < 1 ||
        settings.gridHeight > kMaxGridHeight)
        throw std::invalid_argument("dome fit: the grid must be 1 × 1 to 1024 × 512 cells");
    checkSrbfFitSettings(settings.srbf);
    if (std::string problem = regularFileProblem(path); !problem.empty()) return failure(path, problem);
    std::error_code error;
    const uintmax_t fileSize = std::filesystem::file_size(path, error);
    const auto modified = std::filesystem::last_write_time(path, error);
    if (error) return failure(path, error.message());

    Key key;
    key.path = path;
    key.fileSize = fileSize;
    key.modified = std::chrono::duration_cast<std::chrono::nanoseconds>(modified.time_since_epoch()).count();
    key.layout = "latlong";
    key.gridWidth = settings.gridWidth;
    key.gridHeight = settings.gridHeight;
    key.maxLobes = settings.srbf.maxLobes;
    key.targetError = settings.srbf.targetError;
    key.refinementSweeps = settings.srbf.refinementSweeps;
    key.prefilterBandwidth = settings.srbf.prefilterBandwidth;

    std::promise<Outcome> promise;
    std::shared_future<Outcome> outcome;
    bool found = false;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        auto entry = entries_.find(key);
        found = entry != entries_.end();
        if (found) {
            outcome = entry->second;
        } else {
            outcome = promise.get_future().share();
            entries_.emplace(key, outcome);
            ++fitsComputed_;
        }
    }
    if (found) return outcome.get();  // waits, without the lock, while another thread fits
    try {
        promise.set_value(readAndFit(path, settings));
    } catch (...) {
        // Not a verdict on the file (out of memory, say): forget the entry so
        // that a later call tries again, and let the waiting callers know.
        promise.set_exception(std::current_exception());
        std::lock_guard<std::mutex> lock(mutex_);
        entries_.erase(key);
        throw;
    }
    return outcome.get();
}

size_t DomeTextureFitCache::size() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return entries_.size();
}

size_t DomeTextureFitCache::fitsComputed() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return fitsComputed_;
}

void DomeTextureFitCache::clear() {
    std::lock_guard<std::mutex> lock(mutex_);
    entries_.clear();
    fitsComputed_ = 0;
}

}  // namespace hdhair
