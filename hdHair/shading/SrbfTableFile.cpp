#include "hdHair/shading/SrbfTableFile.h"

#include <cstring>
#include <fstream>

#include "hdHair/base/AtomicFile.h"
#include "hdHair/base/RegularFile.h"

namespace hdhair {
namespace {

constexpr char kMagic[8] = {'h', 'd', 'H', 'S', 'R', 'B', 'F', '\0'};

template <typename T>
void append(std::string& out, const T& value) {
    out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

// Reads fields front to back; any read past the end marks it truncated.
class Reader {
public:
    explicit Reader(const std::string& bytes) : bytes_(bytes) {}
    template <typename T>
    bool read(T& value) {
        if (truncated_ || bytes_.size() - offset_ < sizeof value) return !(truncated_ = true);
        std::memcpy(&value, bytes_.data() + offset_, sizeof value);
        offset_ += sizeof value;
        return true;
    }
    bool read(std::string& out, std::size_t size) {
        if (truncated_ || bytes_.size() - offset_ < size) return !(truncated_ = true);
        out.assign(bytes_, offset_, size);
        offset_ += size;
        return true;
    }
    std::size_t remaining() const { return bytes_.size() - offset_; }
    const char* here() const { return bytes_.data() + offset_; }

private:
    const std::string& bytes_;
    std::size_t offset_ = 0;
    bool truncated_ = false;
};

}  // namespace

std::uint64_t fnv1a64(const void* data, std::size_t size, std::uint64_t seed) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    std::uint64_t hash = seed;
    for (std::size_t i = 0; i < size; ++i) {
        hash ^= bytes[i];
        hash *= 0x100000001b3ull;
    }
    return hash;
}

void writeSrbfTableFile(const std::string& path, const std::string& key, const SrbfConvolutionTable& table) {
    std::string bytes(kMagic, sizeof kMagic);
    append(bytes, kSrbfTableFileVersion);
    append(bytes, std::uint32_t(key.size()));
    bytes += key;
    append(bytes, std::uint32_t(table.kind));
    append(bytes, std::int32_t(table.resolution.azimuths));
    append(bytes, std::int32_t(table.resolution.outgoing));
    append(bytes, std::int32_t(table.resolution.centres));
    append(bytes, std::int32_t(table.resolution.bandwidths));
    append(bytes, std::uint32_t(table.precision));
    append(bytes, std::uint32_t(table.channels));
    const std::size_t payload = table.texels.size() * sizeof(float);
    append(bytes, std::uint64_t(table.texels.size()));
    append(bytes, fnv1a64(table.texels.data(), payload));
    bytes.append(reinterpret_cast<const char*>(table.texels.data()), payload);
    writeFileAtomically(path, [&](const std::string& temporary) -> std::string {
        std::ofstream out(temporary, std::ios::binary);
        out.write(bytes.data(), std::streamsize(bytes.size()));
        out.close();
        return out ? std::string() : std::string("write failed");
    });
}

std::string readSrbfTableFile(const std::string& path, const std::string& key, SrbfConvolutionTable& table) {
    std::string bytes;
    std::string why = readRegularFile(path, bytes);
    if (!why.empty()) return why;
    Reader reader(bytes);
    std::string magic, storedKey;
    std::uint32_t version = 0, keySize = 0, kind = 0, precision = 0, channels = 0;
    std::int32_t size[4] = {0, 0, 0, 0};
    std::uint64_t count = 0, checksum = 0;
    if (!reader.read(magic, sizeof kMagic)) return "truncated header";
    if (magic != std::string(kMagic, sizeof kMagic)) return "not an hdHair SRBF table";
    if (!reader.read(version) || !reader.read(keySize)) return "truncated header";
    if (version != kSrbfTableFileVersion) return "format version " + std::to_string(version);
    if (!reader.read(storedKey, keySize)) return "truncated key";
    if (storedKey != key) return "written for other parameters";
    if (!reader.read(kind) || !reader.read(size[0]) || !reader.read(size[1]) || !reader.read(size[2]) ||
        !reader.read(size[3]) || !reader.read(precision) || !reader.read(channels) || !reader.read(count) ||
        !reader.read(checksum))
        return "truncated header";
    SrbfConvolutionTable result;
    result.kind = SrbfTableKind(kind);
    result.resolution = {size[0], size[1], size[2], size[3]};
    result.precision = SrbfTablePrecision(precision);
    result.channels = int(channels);
    for (std::int32_t s : size)
        if (s < 1 || s > 4096) return "bad resolution";
    if (channels < 1 || channels > 4) return "bad channel count";
    if (count != std::uint64_t(result.width()) * result.height() * result.depth() * result.channels)
        return "texel count does not match the resolution";
    if (reader.remaining() != count * sizeof(float))
        return reader.remaining() < count * sizeof(float) ? "truncated texels" : "trailing bytes";
    if (fnv1a64(reader.here(), reader.remaining()) != checksum) return "checksum mismatch";
    result.texels.resize(count);
    std::memcpy(result.texels.data(), reader.here(), reader.remaining());
    table = std::move(result);
    return std::string();
}

}  // namespace hdhair
