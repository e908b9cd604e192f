#include "hdHair/shading/SrbfTableCache.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "hdHair/base/AtomicFile.h"
#include "hdHair/base/Diagnostics.h"
#include "hdHair/shading/SrbfTableFile.h"

namespace hdhair {
namespace {

namespace fs = std::filesystem;

template <typename T>
void append(std::string& out, const T& value) {
    out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

void appendVector(std::string& out, const glm::vec3& v) {
    for (int i = 0; i < 3; ++i) append(out, v[i]);
}

const char* kindName(SrbfTableKind kind) {
    switch (kind) {
        case SrbfTableKind::MarschnerColour: return "marschner";
        case SrbfTableKind::MarschnerLobes: return "marschner-lobes";
        case SrbfTableKind::KajiyaKay: return "kajiya-kay";
    }
    return "unknown";
}

const char* environment(const char* name) {
    const char* value = std::getenv(name);
    return value != nullptr && *value != '\0' ? value : nullptr;
}

}  // namespace

SrbfTableRequest srbfMarschnerTableRequest(const MarschnerParameters& parameters) {
    SrbfTableRequest request;
    request.kind = SrbfTableKind::MarschnerColour;
    request.marschner = parameters;
    request.resolution = defaultSrbfTableResolution(request.kind);
    return request;
}

SrbfTableRequest srbfMarschnerLobeTableRequest(const MarschnerParameters& parameters) {
    SrbfTableRequest request = srbfMarschnerTableRequest(parameters);
    request.kind = SrbfTableKind::MarschnerLobes;
    request.marschner.sigmaA = glm::vec3(0.0f);
    request.resolution = defaultSrbfTableResolution(request.kind);
    return request;
}

SrbfTableRequest srbfKajiyaKayTableRequest(float shininess) {
    SrbfTableRequest request;
    request.kind = SrbfTableKind::KajiyaKay;
    request.shininess = shininess;
    request.resolution = defaultSrbfTableResolution(request.kind);
    return request;
}

std::string srbfTableKey(const SrbfTableRequest& request) {
    std::string key;
    append(key, kSrbfTableFileVersion);
    append(key, kSrbfTableBuildRevision);
    append(key, std::uint32_t(request.kind));
    const SrbfTableResolution& r = request.resolution;
    for (int size : {r.azimuths, r.outgoing, r.centres, r.bandwidths}) append(key, std::int32_t(size));
    append(key, std::uint32_t(request.precision));
    if (request.kind == SrbfTableKind::KajiyaKay) {
        append(key, request.shininess);
        return key;
    }
    const MarschnerParameters& m = request.marschner;
    append(key, m.eta);
    appendVector(key, m.alpha);
    appendVector(key, m.beta);
    appendVector(key, request.kind == SrbfTableKind::MarschnerColour ? m.sigmaA : glm::vec3(0.0f));
    for (float value : {m.glintScale, m.causticWidth, m.causticFade, m.causticLimit}) append(key, value);
    return key;
}

SrbfConvolutionTable buildSrbfTable(const SrbfTableRequest& request) {
    switch (request.kind) {
        case SrbfTableKind::MarschnerColour:
            return buildSrbfMarschnerTable(request.marschner, request.resolution, request.precision);
        case SrbfTableKind::MarschnerLobes:
            return buildSrbfMarschnerLobeTable(request.marschner, request.resolution, request.precision);
        case SrbfTableKind::KajiyaKay:
            return buildSrbfKajiyaKayTable(request.shininess, request.resolution, request.precision);
    }
    throw std::invalid_argument("unknown SRBF table kind");
}

std::string defaultSrbfCacheDirectory() {
    if (const char* directory = environment("HDHAIR_CACHE_DIR")) return directory;
    if (const char* xdg = environment("XDG_CACHE_HOME")) return (fs::path(xdg) / "hdhair").string();
    if (const char* home = environment("HOME")) return (fs::path(home) / ".cache" / "hdhair").string();
    return std::string();
}

SrbfTableCache::SrbfTableCache(std::string directory) : directory_(std::move(directory)) {}

std::string SrbfTableCache::pathFor(const SrbfTableRequest& request) const {
    if (directory_.empty()) return std::string();
    const std::string key = srbfTableKey(request);
    char name[64];
    std::snprintf(name, sizeof name, "srbf-%s-%016llx.bin", kindName(request.kind),
                  static_cast<unsigned long long>(fnv1a64(key.data(), key.size())));
    return (fs::path(directory_) / name).string();
}

SrbfTableCache::Counts SrbfTableCache::counts() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return counts_;
}

std::shared_ptr<const SrbfConvolutionTable> SrbfTableCache::table(const SrbfTableRequest& request,
                                                                 Diagnostics& diagnostics) {
    const std::string key = srbfTableKey(request);
    std::shared_ptr<Entry> entry;
    bool existed;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        std::shared_ptr<Entry>& slot = entries_[key];
        existed = slot != nullptr;
        if (!existed) slot = std::make_shared<Entry>();
        entry = slot;
    }
    // Later requests for the key wait here for the first one's table.
    std::call_once(entry->once, [&] { entry->table = load(request, key, diagnostics); });
    if (existed) {
        std::lock_guard<std::mutex> lock(mutex_);
        ++counts_.memoryHits;
    }
    return entry->table;
}

std::shared_ptr<const SrbfConvolutionTable> SrbfTableCache::load(const SrbfTableRequest& request,
                                                                const std::string& key, Diagnostics& diagnostics) {
    const std::string path = pathFor(request);
    if (!path.empty() && fs::exists(path)) {
        auto table = std::make_shared<SrbfConvolutionTable>();
        std::string why = readSrbfTableFile(path, key, *table);
        if (why.empty() && table->kind == request.kind && table->precision == request.precision) {
            std::lock_guard<std::mutex> lock(mutex_);
            ++counts_.fileReads;
            return table;
        }
        diagnostics.warn(path, "SRBF table cache file not used (" + (why.empty() ? "kind or precision" : why) +
                                   "); rebuilding it");
    }
    auto table = std::make_shared<SrbfConvolutionTable>(buildSrbfTable(request));
    {
        std::lock_guard<std::mutex> lock(mutex_);
        ++counts_.builds;
    }
    if (path.empty()) return table;
    std::error_code error;
    fs::create_directories(directory_, error);
    std::string why = error ? error.message() : whyNotWritable(path);
    if (why.empty()) {
        try {
            writeSrbfTableFile(path, key, *table);
            std::lock_guard<std::mutex> lock(mutex_);
            ++counts_.fileWrites;
        } catch (const std::exception& failure) {
            why = failure.what();
        }
    }
    if (!why.empty())
        diagnostics.warn(directory_, "SRBF table cache not written (" + why + "); the table is kept in memory only");
    return table;
}

}  // namespace hdhair
