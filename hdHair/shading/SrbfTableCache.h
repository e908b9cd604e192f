#pragma once
// Where SRBF-convolution tables (SrbfConvolutionTables.h) come from at run
// time: memory, else a file in the cache directory, else a build (about a
// second, README) that is then written there. Materials with equal fibre
// parameters share one table.
//
// The key holds everything a table depends on and nothing else: the kind,
// resolution and precision, kSrbfTableFileVersion and kSrbfTableBuildRevision,
// and the fibre parameters: for MarschnerColour η, α_p, β_p, σ_a, k_G, w_c,
// Δη', Δh_M; for MarschnerLobes the same without σ_a; for KajiyaKay the
// shininess p only (Kd, Ks and the colour multiply the table). Floats are
// keyed by their bits.
// Files are named srbf-<kind>-<FNV-1a 64 of the key, 16 hex digits>.bin and
// hold the whole key (SrbfTableFile.h). A file that is missing, unreadable,
// corrupt, truncated, of another version or for another key is a warning
// (Diagnostics, naming the file and what is wrong) and a rebuild that
// replaces it; it never fails the render or serves a wrong table. A cache
// directory that cannot be created or written is a warning too: tables are
// then built per process and kept in memory only.

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "hdHair/shading/SrbfConvolutionTables.h"

namespace hdhair {

class Diagnostics;

// Bump when the build (quadrature, orders, formulas) changes what a table holds.
constexpr std::uint32_t kSrbfTableBuildRevision = 1;

struct SrbfTableRequest {
    SrbfTableKind kind = SrbfTableKind::MarschnerColour;
    MarschnerParameters marschner;  // the Marschner kinds
    float shininess = 60.0f;        // KajiyaKay
    SrbfTableResolution resolution = defaultSrbfTableResolution(SrbfTableKind::MarschnerColour);
    SrbfTablePrecision precision = kSrbfTablePrecision;
};

SrbfTableRequest srbfMarschnerTableRequest(const MarschnerParameters& parameters);
SrbfTableRequest srbfMarschnerLobeTableRequest(const MarschnerParameters& parameters);
SrbfTableRequest srbfKajiyaKayTableRequest(float shininess);

// The key's bytes (above).
std::string srbfTableKey(const SrbfTableRequest& request);
SrbfConvolutionTable buildSrbfTable(const SrbfTableRequest& request);

// $HDHAIR_CACHE_DIR, else $XDG_CACHE_HOME/hdhair, else $HOME/.cache/hdhair
// (empty variables count as unset); "" when none is set.
std::string defaultSrbfCacheDirectory();

class SrbfTableCache {
public:
    // directory "" keeps tables in memory only.
    explicit SrbfTableCache(std::string directory = defaultSrbfCacheDirectory());

    // Thread-safe. Concurrent requests for one key build it once.
    std::shared_ptr<const SrbfConvolutionTable> table(const SrbfTableRequest& request, Diagnostics& diagnostics);

    // The file a request is kept in ("" without a directory).
    std::string pathFor(const SrbfTableRequest& request) const;
    const std::string& directory() const { return directory_; }

    struct Counts {
        int memoryHits = 0, fileReads = 0, builds = 0, fileWrites = 0;
    };
    Counts counts() const;

private:
    struct Entry {
        std::once_flag once;
        std::shared_ptr<const SrbfConvolutionTable> table;
    };
    std::shared_ptr<const SrbfConvolutionTable> load(const SrbfTableRequest& request, const std::string& key,
                                                     Diagnostics& diagnostics);

    std::string directory_;
    mutable std::mutex mutex_;
    std::map<std::string, std::shared_ptr<Entry>> entries_;
    Counts counts_;
};

}  // namespace hdhair
