#pragma once
// Fitting a dome texture costs a read of the whole file and a fit (a
// noticeable fraction of a second for a 1k map); a stage is synced again on every edit and every
// frame of hdhair-record --frames, and several lights or stages may share a
// map. So fits are kept, in memory, for the life of the process, keyed by
//   (resolved path, file size, modification time, layout, grid size, fit settings):
// a file rewritten in place (a new size or time) is read again; the same file
// under the same settings is read once, however many threads ask at once
// (the first computes, the others wait for it). Nothing is written to disk:
// a fit takes a tenth of a second, a disk cache would need invalidation and
// a place to live, and neither is worth it yet.
//
// Outcomes are kept whether they succeeded or not, so an unreadable file is
// not decoded again on every sync; a missing file (no size or time to key
// on) is not kept and is looked for again next time. Entries are a few kB
// (the lobes and the read's facts) and are never evicted; clear() empties
// the cache (tests).

#include <cstddef>
#include <cstdint>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <tuple>

#include "hdHair/environment/SrbfFit.h"

namespace hdhair {

struct DomeFitSettings {
    // The grid the texture is averaged onto before fitting (RadianceGrid.h),
    // 1 × 1 to 1024 × 512 cells (latlongFit throws std::invalid_argument
    // beyond); 64 × 32 cells are 5.6° wide, narrower than the narrowest lobe.
    int gridWidth = 64;
    int gridHeight = 32;
    SrbfFitSettings srbf;

    bool operator==(const DomeFitSettings& other) const {
        return gridWidth == other.gridWidth && gridHeight == other.gridHeight && srbf == other.srbf;
    }
};

// What came of fitting one texture file.
struct DomeTextureFit {
    SrbfFit fit;                // in the dome's frame and the texture's own units
    int imageWidth = 0;         // the file's size in texels
    int imageHeight = 0;
    size_t repairedTexels = 0;  // NaN, infinite or negative texels read as 0 (LatlongTexture.h)
    std::string error;          // not empty: the texture could not be used, and why ("cannot read '...': ...")
};

class DomeTextureFitCache {
public:
    // The process-wide cache.
    static DomeTextureFitCache& process();

    // The fit of the latlong texture at `path` (never null); computed now,
    // or earlier for the same key.
    std::shared_ptr<const DomeTextureFit> latlongFit(const std::string& path, const DomeFitSettings& settings);

    size_t size() const;
    // How many fits this cache has computed (not found): for tests.
    size_t fitsComputed() const;
    void clear();

private:
    struct Key {
        std::string path;
        uintmax_t fileSize = 0;
        int64_t modified = 0;  // nanoseconds since the file clock's epoch
        std::string layout;    // "latlong": the only one fitted so far
        int gridWidth = 0, gridHeight = 0;
        int maxLobes = 0;
        float targetError = 0.0f;
        int refinementSweeps = 0;
        float prefilterBandwidth = 0.0f;

        auto fields() const {
            return std::tie(path, fileSize, modified, layout, gridWidth, gridHeight, maxLobes, targetError,
                            refinementSweeps, prefilterBandwidth);
        }
        bool operator<(const Key& other) const { return fields() < other.fields(); }
    };
    using Outcome = std::shared_ptr<const DomeTextureFit>;

    mutable std::mutex mutex_;
    std::map<Key, std::shared_future<Outcome>> entries_;
    size_t fitsComputed_ = 0;
};

}  // namespace hdhair
