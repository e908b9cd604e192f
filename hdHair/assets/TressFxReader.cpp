#include "hdHair/assets/TressFxReader.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include <fmt/format.h>

#include "hdHair/base/RegularFile.h"

namespace hdhair::convert {

namespace {

constexpr uint64_t kHeader40Size = 160;        // 8 words + 32 reserved words
constexpr uint64_t kHeader30MinSize = 37 * 4;  // up to and including word 36
constexpr int kOffsetWord30 = 36;
// Far beyond any real asset; keeps size arithmetic well inside 64 bits.
constexpr uint64_t kMaxVerticesPerStrand = 1u << 16;

uint32_t readU32(const std::vector<uint8_t>& bytes, uint64_t offset) {
    uint32_t value = 0;
    std::memcpy(&value, bytes.data() + offset, sizeof value);  // little-endian hosts only
    return value;
}

float readF32(const std::vector<uint8_t>& bytes, uint64_t offset) {
    float value = 0.0f;
    std::memcpy(&value, bytes.data() + offset, sizeof value);
    return value;
}

[[noreturn]] void fail(const std::string& name, const std::string& what) {
    throw std::runtime_error(name + ": " + what);
}

// An array of `bytesNeeded` bytes at `offset`, checked against the header and the file.
void checkArray(const std::string& name, const std::string& what, uint64_t offset, uint64_t bytesNeeded,
                uint64_t headerSize, uint64_t fileSize) {
    if (offset < headerSize)
        fail(name, fmt::format("{} at byte {} overlap the {}-byte header", what, offset, headerSize));
    if (offset > fileSize || bytesNeeded > fileSize - offset)
        fail(name, fmt::format("{} at byte {} run past the end of the {}-byte file (they end at byte {})", what,
                               offset, fileSize, offset + bytesNeeded));
}

void checkCounts(const std::string& name, uint32_t strands, uint32_t verticesPerStrand) {
    if (strands == 0) fail(name, "the header says the file has 0 strands");
    if (verticesPerStrand < 2)
        fail(name, fmt::format("the header says {} vertices per strand (a strand needs at least 2)",
                               verticesPerStrand));
    if (verticesPerStrand > kMaxVerticesPerStrand)
        fail(name, fmt::format("the header says {} vertices per strand (at most {} are read)", verticesPerStrand,
                               kMaxVerticesPerStrand));
}

void readPositions(const std::vector<uint8_t>& bytes, const std::string& name, uint64_t offset, uint32_t strands,
                   uint32_t verticesPerStrand, uint64_t stride, HairStrands& out) {
    const uint64_t total = uint64_t{strands} * verticesPerStrand;
    out.vertexCounts.assign(strands, static_cast<int>(verticesPerStrand));
    out.points.resize(total);
    for (uint64_t i = 0; i < total; ++i) {
        const uint64_t at = offset + i * stride;
        Float3 p{readF32(bytes, at), readF32(bytes, at + 4), readF32(bytes, at + 8)};
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            fail(name, fmt::format("vertex {} of strand {} (byte {}) is not finite: ({}, {}, {})",
                                   i % verticesPerStrand, i / verticesPerStrand, at, p.x, p.y, p.z));
        out.points[i] = p;
    }
}

HairStrands parse40(const std::vector<uint8_t>& bytes, const std::string& name) {
    const uint64_t fileSize = bytes.size();
    if (fileSize < kHeader40Size)
        fail(name, fmt::format("the {}-byte file is too small for a TressFX 4.0 header ({} bytes)", fileSize,
                               kHeader40Size));
    const uint32_t strands = readU32(bytes, 4), verticesPerStrand = readU32(bytes, 8);
    checkCounts(name, strands, verticesPerStrand);
    const uint64_t vertices = uint64_t{strands} * verticesPerStrand;
    const uint32_t offsetPositions = readU32(bytes, 12), offsetStrandUV = readU32(bytes, 16),
                   offsetVertexUV = readU32(bytes, 20), offsetStrandThickness = readU32(bytes, 24),
                   offsetVertexColor = readU32(bytes, 28);
    if (offsetPositions == 0) fail(name, "the header has no positions (offsetVertexPosition is 0)");
    checkArray(name,
               fmt::format("positions ({} strands x {} vertices x 16 bytes)", strands, verticesPerStrand),
               offsetPositions, vertices * 16, kHeader40Size, fileSize);
    if (offsetStrandUV != 0)
        checkArray(name, fmt::format("strand UVs ({} strands x 8 bytes)", strands), offsetStrandUV,
                   uint64_t{strands} * 8, kHeader40Size, fileSize);
    if (offsetVertexUV != 0)
        checkArray(name, fmt::format("vertex UVs ({} vertices x 8 bytes)", vertices), offsetVertexUV, vertices * 8,
                   kHeader40Size, fileSize);
    if (offsetStrandThickness != 0)
        checkArray(name, fmt::format("strand thicknesses ({} strands x 4 bytes)", strands), offsetStrandThickness,
                   uint64_t{strands} * 4, kHeader40Size, fileSize);
    if (offsetVertexColor != 0)
        checkArray(name, fmt::format("vertex colors ({} vertices x 16 bytes)", vertices), offsetVertexColor,
                   vertices * 16, kHeader40Size, fileSize);

    HairStrands out;
    out.source = name;
    out.format = "TressFX 4.0";
    readPositions(bytes, name, offsetPositions, strands, verticesPerStrand, 16, out);
    if (offsetStrandThickness != 0) {
        out.strandThickness.resize(strands);
        for (uint32_t s = 0; s < strands; ++s) {
            float t = readF32(bytes, offsetStrandThickness + uint64_t{s} * 4);
            if (!std::isfinite(t) || t < 0.0f)
                fail(name, fmt::format("the thickness of strand {} is {} (must be finite and not negative)", s, t));
            out.strandThickness[s] = t;
        }
    }
    return out;
}

HairStrands parse30(const std::vector<uint8_t>& bytes, const std::string& name) {
    const uint64_t fileSize = bytes.size();
    if (fileSize < kHeader30MinSize)
        fail(name, fmt::format("the {}-byte file is too small for a TressFX 3.0 header (at least {} bytes)", fileSize,
                               kHeader30MinSize));
    const uint32_t strands = readU32(bytes, 4), verticesPerStrand = readU32(bytes, 8);
    checkCounts(name, strands, verticesPerStrand);
    const uint32_t offsetPositions = readU32(bytes, kOffsetWord30 * 4);
    checkArray(name,
               fmt::format("positions ({} strands x {} vertices x 12 bytes)", strands, verticesPerStrand),
               offsetPositions, uint64_t{strands} * verticesPerStrand * 12, kHeader30MinSize, fileSize);
    HairStrands out;
    out.source = name;
    out.format = "TressFX 3.0";
    readPositions(bytes, name, offsetPositions, strands, verticesPerStrand, 12, out);
    return out;
}

}  // namespace

std::string displayName(const std::string& path) {
    std::string name = std::filesystem::path(path).filename().string();
    return name.empty() ? path : name;
}

std::vector<uint8_t> readFileBytes(const std::string& path) {
    std::string contents;
    const std::string error = readRegularFile(path, contents);
    if (!error.empty()) fail(displayName(path), "cannot open (" + error + ")");
    return std::vector<uint8_t>(contents.begin(), contents.end());
}

HairStrands parseTressFx(const std::vector<uint8_t>& bytes, const std::string& name) {
    if (bytes.size() < 12)
        fail(name, fmt::format("the {}-byte file is too small for a TressFX header", bytes.size()));
    const float version = readF32(bytes, 0);
    if (version == 4.0f) return parse40(bytes, name);
    if (version == 3.0f) return parse30(bytes, name);
    fail(name, fmt::format("unsupported TressFX version {} (the first 4 bytes; 3.0 and 4.0 are read)", version));
}

HairStrands readTressFx(const std::string& path) { return parseTressFx(readFileBytes(path), displayName(path)); }

}  // namespace hdhair::convert
