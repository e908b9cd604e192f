#include "hdHair/assets/YukselHairReader.h"

#include <cmath>
#include <cstring>
#include <stdexcept>

#include <fmt/format.h>

namespace hdhair::convert {

namespace {

constexpr uint64_t kHeaderSize = 128;
constexpr uint32_t kSegmentsBit = 1u << 0, kPointsBit = 1u << 1, kThicknessBit = 1u << 2,
                   kTransparencyBit = 1u << 3, kColorsBit = 1u << 4;

[[noreturn]] void fail(const std::string& name, const std::string& what) {
    throw std::runtime_error(name + ": " + what);
}

template <typename T>
T readValue(const std::vector<uint8_t>& bytes, uint64_t offset) {
    T value{};
    std::memcpy(&value, bytes.data() + offset, sizeof value);  // little-endian hosts only
    return value;
}

// Walks the arrays after the header, checking each against the file size.
class ArrayCursor {
public:
    ArrayCursor(const std::vector<uint8_t>& bytes, const std::string& name) : bytes_(bytes), name_(name) {}

    // Reserves `count` elements of `elementSize` bytes and returns their byte offset.
    uint64_t take(const std::string& what, uint64_t count, uint64_t elementSize) {
        const uint64_t at = offset_, size = count * elementSize, fileSize = bytes_.size();
        if (at > fileSize || size > fileSize - at)
            fail(name_, fmt::format("{} ({} x {} bytes) at byte {} run past the end of the {}-byte file (they end "
                                    "at byte {})",
                                    what, count, elementSize, at, fileSize, at + size));
        offset_ += size;
        return at;
    }

private:
    const std::vector<uint8_t>& bytes_;
    const std::string& name_;
    uint64_t offset_ = kHeaderSize;
};

float finite(const std::string& name, float value, const std::string& what, uint64_t point) {
    if (!std::isfinite(value)) fail(name, fmt::format("the {} of point {} is not finite ({})", what, point, value));
    return value;
}

// Three finite floats at byte `at`: point `point`'s position or colour.
Float3 finiteVec3(const std::vector<uint8_t>& bytes, uint64_t at, const std::string& name, const std::string& what,
                     uint64_t point) {
    return {finite(name, readValue<float>(bytes, at), what, point),
            finite(name, readValue<float>(bytes, at + 4), what, point),
            finite(name, readValue<float>(bytes, at + 8), what, point)};
}

// Clamps values to [minimum, maximum], counting those it moved.
struct RangeRepair {
    const char* what;
    float minimum, maximum;
    size_t count = 0;
    float example = 0.0f;

    float clamp(float value) {
        if (value >= minimum && value <= maximum) return value;
        if (count++ == 0) example = value;
        return std::min(std::max(value, minimum), maximum);
    }
};

// The 128-byte header's counts, array bits and the defaults for arrays not
// present.
struct YukselHeader {
    uint32_t hairCount, pointCount, arrays, defaultSegments;
    float defaultThickness, defaultTransparency;
    Float3 defaultColor;
};

YukselHeader readHeader(const std::vector<uint8_t>& bytes, const std::string& name) {
    if (bytes.size() < kHeaderSize)
        fail(name, fmt::format("the {}-byte file is too small for a .hair header ({} bytes)", bytes.size(),
                               kHeaderSize));
    if (std::memcmp(bytes.data(), "HAIR", 4) != 0) fail(name, "not a .hair file (the first 4 bytes are not \"HAIR\")");
    const YukselHeader header{readValue<uint32_t>(bytes, 4),
                              readValue<uint32_t>(bytes, 8),
                              readValue<uint32_t>(bytes, 12),
                              readValue<uint32_t>(bytes, 16),
                              readValue<float>(bytes, 20),
                              readValue<float>(bytes, 24),
                              {readValue<float>(bytes, 28), readValue<float>(bytes, 32), readValue<float>(bytes, 36)}};

    if (header.hairCount == 0) fail(name, "the header says the file has 0 hairs");
    if (!(header.arrays & kPointsBit)) fail(name, "the file has no points array (bit 1 of the array bit field is 0)");
    return header;
}

// The segment counts' byte offset (0 when every hair has the default count,
// which must then be usable).
uint64_t takeSegmentCounts(ArrayCursor& cursor, const YukselHeader& header, const std::string& name) {
    if (header.arrays & kSegmentsBit) return cursor.take("segment counts", header.hairCount, 2);
    if (header.defaultSegments == 0 || header.defaultSegments > 65535) {
        fail(name, fmt::format("the header's default segment count is {} (1 to 65535) and there is no segments "
                               "array",
                               header.defaultSegments));
    }
    return 0;
}

void readVertexCounts(const std::vector<uint8_t>& bytes, const YukselHeader& header, uint64_t segmentsAt,
                      const std::string& name, HairStrands& out) {
    out.vertexCounts.resize(header.hairCount);
    uint64_t sum = 0;
    if (header.arrays & kSegmentsBit) {
        for (uint32_t h = 0; h < header.hairCount; ++h) {
            const uint16_t segments = readValue<uint16_t>(bytes, segmentsAt + uint64_t{h} * 2);
            if (segments == 0) fail(name, fmt::format("hair {} has 0 segments", h));
            out.vertexCounts[h] = segments + 1;
            sum += segments + 1u;
        }
    } else {
        out.vertexCounts.assign(header.hairCount, static_cast<int>(header.defaultSegments + 1));
        sum = header.pointCount;
    }
    if (sum != header.pointCount)
        fail(name, fmt::format("the header says {} points but the {} hairs' segments need {}", header.pointCount,
                               header.hairCount, sum));
}

void readThicknesses(const std::vector<uint8_t>& bytes, const YukselHeader& header, ArrayCursor& cursor,
                     const std::string& name, HairStrands& out) {
    if (header.arrays & kThicknessBit) {
        const uint64_t at = cursor.take("thicknesses", header.pointCount, 4);
        out.widths.resize(header.pointCount);
        for (uint64_t i = 0; i < header.pointCount; ++i) {
            const float w = finite(name, readValue<float>(bytes, at + i * 4), "thickness", i);
            if (w < 0.0f) fail(name, fmt::format("the thickness of point {} is negative ({})", i, w));
            out.widths[i] = w;
        }
    } else if (std::isfinite(header.defaultThickness) && header.defaultThickness > 0.0f) {
        out.defaultWidth = header.defaultThickness;
    }
}

// Opacities, from the file's transparencies.
void readTransparencies(const std::vector<uint8_t>& bytes, const YukselHeader& header, ArrayCursor& cursor,
                        const std::string& name, RangeRepair& transparency, HairStrands& out) {
    if (header.arrays & kTransparencyBit) {
        const uint64_t at = cursor.take("transparencies", header.pointCount, 4);
        out.opacities.resize(header.pointCount);
        for (uint64_t i = 0; i < header.pointCount; ++i)
            out.opacities[i] =
                1.0f - transparency.clamp(finite(name, readValue<float>(bytes, at + i * 4), "transparency", i));
    } else if (std::isfinite(header.defaultTransparency) && header.defaultTransparency > 0.0f) {
        out.defaultOpacity = 1.0f - transparency.clamp(header.defaultTransparency);
    }
}

void readColors(const std::vector<uint8_t>& bytes, const YukselHeader& header, ArrayCursor& cursor,
                const std::string& name, RangeRepair& color, HairStrands& out) {
    const Float3& defaultColor = header.defaultColor;
    if (header.arrays & kColorsBit) {
        const uint64_t at = cursor.take("colors", header.pointCount, 12);
        out.colors.resize(header.pointCount);
        for (uint64_t i = 0; i < header.pointCount; ++i) {
            const Float3 c = finiteVec3(bytes, at + i * 12, name, "color", i);
            out.colors[i] = {color.clamp(c.x), color.clamp(c.y), color.clamp(c.z)};
        }
    } else if (std::isfinite(defaultColor.x) && std::isfinite(defaultColor.y) && std::isfinite(defaultColor.z) &&
               !(defaultColor == Float3{})) {
        out.defaultColor = Float3{color.clamp(defaultColor.x), color.clamp(defaultColor.y), color.clamp(defaultColor.z)};
    }
}

}  // namespace

HairStrands parseYukselHair(const std::vector<uint8_t>& bytes, const std::string& name) {
    const YukselHeader header = readHeader(bytes, name);
    const uint32_t hairCount = header.hairCount, pointCount = header.pointCount;

    // Every array the header announces is checked against the bytes
    // present before anything is sized by the header's counts: a 192-byte
    // file claiming four billion hairs fails here, allocating nothing.
    ArrayCursor cursor(bytes, name);
    const uint64_t segmentsAt = takeSegmentCounts(cursor, header, name);
    const uint64_t pointsAt = cursor.take("points", pointCount, 12);
    if (!(header.arrays & kSegmentsBit) && uint64_t{hairCount} * (header.defaultSegments + 1) != pointCount)
        fail(name, fmt::format("the header says {} points but the {} hairs' segments need {}", pointCount, hairCount,
                               uint64_t{hairCount} * (header.defaultSegments + 1)));

    HairStrands out;
    out.source = name;
    out.format = "Cem Yuksel .hair";
    readVertexCounts(bytes, header, segmentsAt, name, out);
    out.points.resize(pointCount);
    for (uint64_t i = 0; i < pointCount; ++i) {
        out.points[i] = finiteVec3(bytes, pointsAt + i * 12, name, "position", i);
    }
    readThicknesses(bytes, header, cursor, name, out);
    // Transparency is a fraction and colour is linear light: values beyond
    // [0, 1] or below 0 are clamped, with one repair noted per array.
    RangeRepair transparency{"transparency", 0.0f, 1.0f}, color{"colour component", 0.0f, INFINITY};
    readTransparencies(bytes, header, cursor, name, transparency, out);
    readColors(bytes, header, cursor, name, color, out);
    for (const RangeRepair* repair : {&transparency, &color})
        if (repair->count > 0)
            out.repairs.push_back(fmt::format("{} {} value(s) outside [{}, {}] (e.g. {}); clamped", repair->count,
                                              repair->what, repair->minimum, repair->maximum, repair->example));
    return out;
}

HairStrands readYukselHair(const std::string& path) {
    return parseYukselHair(readFileBytes(path), displayName(path));
}

}  // namespace hdhair::convert
