// The SRBF table cache (SrbfTableCache.h, SrbfTableFile.h): keys, the cache
// directory's precedence, the round trip through a file, and every way a
// cache file can be bad (each a warning and a rebuild, never a wrong table).

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/shading/SrbfTableCache.h"
#include "hdHair/shading/SrbfTableFile.h"

using namespace hdhair;
namespace fs = std::filesystem;

namespace {

// A small table, so each build takes milliseconds.
SrbfTableRequest smallRequest(const glm::vec3& sigmaA = glm::vec3(0.15f, 0.3f, 0.6f)) {
    MarschnerParameters parameters;
    parameters.sigmaA = sigmaA;
    SrbfTableRequest request = srbfMarschnerTableRequest(parameters);
    request.resolution = {4, 6, 6, 2};
    return request;
}

class TemporaryDirectory {
public:
    TemporaryDirectory() {
        std::random_device device;
        path_ = fs::temp_directory_path() / ("hdhair-srbf-cache-" + std::to_string(device()));
        fs::create_directories(path_);
    }
    ~TemporaryDirectory() {
        std::error_code error;
        fs::remove_all(path_, error);
    }
    std::string path() const { return path_.string(); }

private:
    fs::path path_;
};

// Sets an environment variable for one scope (unset when value is null).
class ScopedEnvironment {
public:
    ScopedEnvironment(const char* name, const char* value) : name_(name) {
        if (const char* old = std::getenv(name)) old_ = old, hadOld_ = true;
        if (value) ::setenv(name, value, 1);
        else ::unsetenv(name);
    }
    ~ScopedEnvironment() {
        if (hadOld_) ::setenv(name_.c_str(), old_.c_str(), 1);
        else ::unsetenv(name_.c_str());
    }

private:
    std::string name_, old_;
    bool hadOld_ = false;
};

bool bitIdentical(const SrbfConvolutionTable& a, const SrbfConvolutionTable& b) {
    return a.kind == b.kind && a.resolution == b.resolution && a.precision == b.precision &&
           a.channels == b.channels && a.texels.size() == b.texels.size() &&
           std::memcmp(a.texels.data(), b.texels.data(), a.texels.size() * sizeof(float)) == 0;
}

std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void writeBytes(const std::string& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), std::streamsize(bytes.size()));
}

}  // namespace

TEST(SrbfTableCache, DirectoryPrecedence) {
    ScopedEnvironment home("HOME", "/home/someone");
    {
        ScopedEnvironment own("HDHAIR_CACHE_DIR", "/tmp/own");
        ScopedEnvironment xdg("XDG_CACHE_HOME", "/tmp/xdg");
        EXPECT_EQ(defaultSrbfCacheDirectory(), "/tmp/own");
    }
    {
        ScopedEnvironment own("HDHAIR_CACHE_DIR", "");
        ScopedEnvironment xdg("XDG_CACHE_HOME", "/tmp/xdg");
        EXPECT_EQ(defaultSrbfCacheDirectory(), "/tmp/xdg/hdhair");
    }
    {
        ScopedEnvironment own("HDHAIR_CACHE_DIR", nullptr);
        ScopedEnvironment xdg("XDG_CACHE_HOME", nullptr);
        EXPECT_EQ(defaultSrbfCacheDirectory(), "/home/someone/.cache/hdhair");
        ScopedEnvironment noHome("HOME", nullptr);
        EXPECT_EQ(defaultSrbfCacheDirectory(), "");
    }
}

TEST(SrbfTableCache, KeysHoldWhatTheTableDependsOnAndNothingElse) {
    SrbfTableCache cache("/cache");
    const SrbfTableRequest brown = smallRequest(), blonde = smallRequest(glm::vec3(0.015f, 0.035f, 0.075f));
    EXPECT_NE(cache.pathFor(brown), cache.pathFor(blonde));
    SrbfTableRequest eccentric = brown;
    eccentric.marschner.eccentricity = 0.9f;  // not modelled: the same table
    EXPECT_EQ(cache.pathFor(brown), cache.pathFor(eccentric));
    SrbfTableRequest wider = brown;
    wider.marschner.beta.x *= 1.5f;
    EXPECT_NE(cache.pathFor(brown), cache.pathFor(wider));
    SrbfTableRequest finer = brown;
    finer.resolution.outgoing = 8;
    EXPECT_NE(cache.pathFor(brown), cache.pathFor(finer));
    SrbfTableRequest single = brown;
    single.precision = SrbfTablePrecision::Float;
    EXPECT_NE(cache.pathFor(brown), cache.pathFor(single));
    // The lobe table does not depend on σ_a; Kajiya-Kay only on its shininess.
    EXPECT_EQ(cache.pathFor(srbfMarschnerLobeTableRequest(brown.marschner)),
              cache.pathFor(srbfMarschnerLobeTableRequest(blonde.marschner)));
    EXPECT_NE(cache.pathFor(srbfKajiyaKayTableRequest(60.0f)), cache.pathFor(srbfKajiyaKayTableRequest(80.0f)));
    EXPECT_EQ(cache.pathFor(brown).rfind("/cache/srbf-marschner-", 0), 0u);
    EXPECT_EQ(SrbfTableCache("").pathFor(brown), "");
}

TEST(SrbfTableCache, RoundTripIsBitIdentical) {
    TemporaryDirectory directory;
    const SrbfTableRequest request = smallRequest();
    Diagnostics diagnostics;
    SrbfTableCache first(directory.path());
    auto built = first.table(request, diagnostics);
    EXPECT_EQ(first.counts().builds, 1);
    EXPECT_EQ(first.counts().fileWrites, 1);
    ASSERT_TRUE(fs::exists(first.pathFor(request)));
    EXPECT_TRUE(bitIdentical(*built, buildSrbfTable(request)));
    // The same cache again: memory.
    EXPECT_EQ(first.table(request, diagnostics).get(), built.get());
    EXPECT_EQ(first.counts().memoryHits, 1);
    // A new process (a new cache on the same directory): the file.
    SrbfTableCache second(directory.path());
    auto read = second.table(request, diagnostics);
    EXPECT_EQ(second.counts().fileReads, 1);
    EXPECT_EQ(second.counts().builds, 0);
    EXPECT_TRUE(bitIdentical(*read, *built));
    EXPECT_EQ(diagnostics.warningCount(), 0u);
    // Kajiya-Kay and the lobe table round-trip too.
    for (const SrbfTableRequest& other :
         {srbfKajiyaKayTableRequest(60.0f), srbfMarschnerLobeTableRequest(request.marschner)}) {
        SrbfTableRequest small = other;
        small.resolution = {other.kind == SrbfTableKind::KajiyaKay ? 1 : 4, 6, 6, 2};
        auto a = first.table(small, diagnostics);
        auto b = SrbfTableCache(directory.path()).table(small, diagnostics);
        EXPECT_TRUE(bitIdentical(*a, *b));
    }
    EXPECT_EQ(diagnostics.warningCount(), 0u);
}

TEST(SrbfTableCache, BadFilesAreAWarningAndARebuild) {
    TemporaryDirectory directory;
    const SrbfTableRequest request = smallRequest();
    const SrbfConvolutionTable expected = buildSrbfTable(request);
    Diagnostics setup;
    SrbfTableCache(directory.path()).table(request, setup);
    const std::string path = SrbfTableCache(directory.path()).pathFor(request);
    const std::string good = readBytes(path);
    ASSERT_GT(good.size(), 100u);
    // Another request's file under this one's name (as a name-hash collision would be).
    const SrbfTableRequest otherRequest = smallRequest(glm::vec3(1.0f, 2.0f, 3.0f));
    SrbfTableCache(directory.path()).table(otherRequest, setup);
    const std::string other = readBytes(SrbfTableCache(directory.path()).pathFor(otherRequest));

    std::string flipped = good;
    flipped[flipped.size() - 7] ^= 0x40;  // a texel bit
    std::string badVersion = good;
    badVersion[8] ^= 0x01;
    std::string badMagic = good;
    badMagic[0] = 'X';
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"checksum", flipped},
        {"truncated texels", good.substr(0, good.size() - 5)},
        {"truncated", good.substr(0, 30)},
        {"trailing", good + "x"},
        {"version", badVersion},
        {"not an hdHair", badMagic},
        {"other parameters", other},
        {"truncated", std::string()},
    };
    for (const auto& [reason, bytes] : cases) {
        writeBytes(path, bytes);
        Diagnostics diagnostics;
        SrbfTableCache cache(directory.path());
        auto table = cache.table(request, diagnostics);
        ASSERT_EQ(diagnostics.warningCount(), 1u) << reason;
        EXPECT_NE(diagnostics.warnings()[0].message.find(reason), std::string::npos)
            << reason << ": " << diagnostics.warnings()[0].message;
        EXPECT_EQ(diagnostics.warnings()[0].where, path);
        EXPECT_EQ(cache.counts().builds, 1) << reason;
        EXPECT_TRUE(bitIdentical(*table, expected)) << reason;
        // The rebuild replaced the file with a good one.
        EXPECT_EQ(readBytes(path), good) << reason;
    }
}

TEST(SrbfTableCache, UnwritableDirectoryKeepsTablesInMemory) {
    TemporaryDirectory directory;
    const std::string notADirectory = (fs::path(directory.path()) / "file").string();
    writeBytes(notADirectory, "x");
    Diagnostics diagnostics;
    SrbfTableCache cache((fs::path(notADirectory) / "cache").string());
    auto table = cache.table(smallRequest(), diagnostics);
    ASSERT_NE(table, nullptr);
    EXPECT_TRUE(bitIdentical(*table, buildSrbfTable(smallRequest())));
    EXPECT_EQ(diagnostics.warningCount(), 1u);
    EXPECT_EQ(cache.counts().fileWrites, 0);
    SrbfTableCache memoryOnly("");
    memoryOnly.table(smallRequest(), diagnostics);
    EXPECT_EQ(diagnostics.warningCount(), 1u);  // no directory asked for, nothing to warn about
}

TEST(SrbfTableCache, ConcurrentRequestsBuildOnce) {
    TemporaryDirectory directory;
    SrbfTableCache cache(directory.path());
    Diagnostics diagnostics;
    std::vector<std::thread> threads;
    std::vector<const SrbfConvolutionTable*> tables(4, nullptr);
    for (int i = 0; i < 4; ++i)
        threads.emplace_back([&, i] { tables[std::size_t(i)] = cache.table(smallRequest(), diagnostics).get(); });
    for (std::thread& thread : threads) thread.join();
    EXPECT_EQ(cache.counts().builds, 1);
    EXPECT_EQ(cache.counts().memoryHits, 3);
    for (const SrbfConvolutionTable* table : tables) EXPECT_EQ(table, tables[0]);
}
