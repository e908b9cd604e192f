// hdhair-convert's readers and writer: synthetic .tfx (3.0, 4.0) and .hair
// files written byte by byte into a temporary folder, the exact errors of
// malformed ones, the written .usda read back with hdHair's embedded reader,
// and (when ../shared/data is there) AMD's real TressFX assets.

#include <sys/stat.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/scene/Scene.h"
#include "hdHair/assets/ObjMeshReader.h"
#include "hdHair/assets/TressFxReader.h"
#include "hdHair/assets/UsdaCurvesWriter.h"
#include "hdHair/assets/YukselHairReader.h"
#include "hdHair/usda/SceneReader.h"
#include "hdHair/usda/Stage.h"

#ifndef HDHAIR_SHARED_DATA_DIR
#define HDHAIR_SHARED_DATA_DIR "../shared/data"
#endif

namespace fs = std::filesystem;
using namespace hdhair::convert;

namespace {

// Little-endian bytes, as the formats store them.
class Bytes {
public:
    Bytes& u32(uint32_t v) { return raw(&v, 4); }
    Bytes& u16(uint16_t v) { return raw(&v, 2); }
    Bytes& f32(float v) { return raw(&v, 4); }
    Bytes& text(const char* s, size_t n) { return raw(s, n); }
    Bytes& zeros(size_t n) {
        data.insert(data.end(), n, 0);
        return *this;
    }
    size_t size() const { return data.size(); }
    std::vector<uint8_t> data;

private:
    Bytes& raw(const void* p, size_t n) {
        const auto* b = static_cast<const uint8_t*>(p);
        data.insert(data.end(), b, b + n);
        return *this;
    }
};

// Strand s, vertex v of the synthetic assets: easy to check, never on a grid line.
Float3 syntheticPoint(uint32_t s, uint32_t v) {
    return {0.5f + float(s), 10.0f - 1.5f * float(v), 0.25f * float(s + v)};
}

// A TressFX 4.0 file: 160-byte header, float4 positions at byte 160 (w = 1
// except the root, 0 = pinned), then optional strand thicknesses.
Bytes tfx40(uint32_t strands, uint32_t vertices, bool thickness = false) {
    Bytes b;
    const uint32_t positions = 160, thicknessAt = positions + strands * vertices * 16;
    b.f32(4.0f).u32(strands).u32(vertices).u32(positions).u32(0).u32(0).u32(thickness ? thicknessAt : 0).u32(0);
    b.zeros(32 * 4);
    for (uint32_t s = 0; s < strands; ++s)
        for (uint32_t v = 0; v < vertices; ++v) {
            Float3 p = syntheticPoint(s, v);
            b.f32(p.x).f32(p.y).f32(p.z).f32(v == 0 ? 0.0f : 1.0f);
        }
    if (thickness)
        for (uint32_t s = 0; s < strands; ++s) b.f32(0.5f + 0.25f * float(s));
    return b;
}

// A TressFX 3.0 file: version, strands, vertices, zeros up to word 36 (the
// positions' offset, 296 as in AMD's samples), zeros to byte 296, float3 positions.
Bytes tfx30(uint32_t strands, uint32_t vertices) {
    Bytes b;
    b.f32(3.0f).u32(strands).u32(vertices);
    b.zeros(36 * 4 - b.size());
    b.u32(296);
    b.zeros(296 - b.size());
    for (uint32_t s = 0; s < strands; ++s)
        for (uint32_t v = 0; v < vertices; ++v) {
            Float3 p = syntheticPoint(s, v);
            b.f32(p.x).f32(p.y).f32(p.z);
        }
    return b;
}

struct HairFile {
    std::vector<uint16_t> segments = {2, 1};  // 3 + 2 points
    uint32_t arrays = 0x1f;
    uint32_t defaultSegments = 4;
    float defaultThickness = 0.5f, defaultTransparency = 0.25f;
    Float3 defaultColor{0.1f, 0.2f, 0.3f};
    int pointCountAdjust = 0;

    uint32_t points() const {
        uint32_t n = 0;
        if (arrays & 1)
            for (uint16_t s : segments) n += s + 1u;
        else
            n = uint32_t(segments.size()) * (defaultSegments + 1);
        return n;
    }
    static Float3 point(uint32_t i) { return {float(i), 2.0f * float(i), -0.5f * float(i)}; }
    static float thickness(uint32_t i) { return 0.1f + 0.01f * float(i); }
    static float transparency(uint32_t i) { return 0.05f * float(i); }
    static Float3 color(uint32_t i) { return {0.1f * float(i), 0.5f, 1.0f - 0.1f * float(i)}; }

    Bytes bytes() const {
        Bytes b;
        const uint32_t n = points();
        b.text("HAIR", 4).u32(uint32_t(segments.size())).u32(uint32_t(int(n) + pointCountAdjust)).u32(arrays);
        b.u32(defaultSegments).f32(defaultThickness).f32(defaultTransparency);
        b.f32(defaultColor.x).f32(defaultColor.y).f32(defaultColor.z);
        char info[88] = "synthetic test hair";
        b.text(info, sizeof info);
        if (arrays & 1)
            for (uint16_t s : segments) b.u16(s);
        if (arrays & 2)
            for (uint32_t i = 0; i < n; ++i) b.f32(point(i).x).f32(point(i).y).f32(point(i).z);
        if (arrays & 4)
            for (uint32_t i = 0; i < n; ++i) b.f32(thickness(i));
        if (arrays & 8)
            for (uint32_t i = 0; i < n; ++i) b.f32(transparency(i));
        if (arrays & 16)
            for (uint32_t i = 0; i < n; ++i) b.f32(color(i).x).f32(color(i).y).f32(color(i).z);
        return b;
    }
};

class HairImport : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               ("hdhair-import-" + std::string(info->test_suite_name()) + "-" + info->name() + "-" +
                std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override {
        std::error_code ignored;
        fs::remove_all(dir_, ignored);
    }

    std::string write(const std::string& name, const std::vector<uint8_t>& data) {
        const std::string path = (dir_ / name).string();
        std::ofstream out(path, std::ios::binary);
        out.write(reinterpret_cast<const char*>(data.data()), std::streamsize(data.size()));
        return path;
    }
    std::string write(const std::string& name, const Bytes& b) { return write(name, b.data); }

    // The message of the std::runtime_error `f` throws ("" when none).
    template <typename F>
    static std::string errorOf(F f) {
        try {
            f();
        } catch (const std::runtime_error& e) {
            return e.what();
        }
        return "";
    }

    fs::path dir_;
};

void expectPoint(const Float3& actual, const Float3& expected) {
    EXPECT_FLOAT_EQ(actual.x, expected.x);
    EXPECT_FLOAT_EQ(actual.y, expected.y);
    EXPECT_FLOAT_EQ(actual.z, expected.z);
}

struct ReadBack {
    std::unique_ptr<hdhair::usda::Stage> stage;
    hdhair::Scene scene;
    hdhair::Diagnostics diagnostics;
};

std::unique_ptr<ReadBack> readBack(const std::string& text) {
    auto r = std::make_unique<ReadBack>();
    r->stage = hdhair::usda::Stage::openFromString(text, "converted.usda");
    hdhair::usda::readScene(*r->stage, 0.0, r->scene, r->diagnostics);
    return r;
}

HairStrands twoStrands() {
    HairStrands s;
    s.source = "two.tfx";
    s.format = "test";
    s.vertexCounts = {3, 4};
    s.points = {{0, 10, 0}, {0, 5, 1}, {0, 0, 2}, {4, 10, 0}, {4, 7, 0}, {5, 4, 0}, {6, 1, -1}};
    return s;
}

// Every point inside 86% of the camera's view (it frames them into 85%) and its clipping range.
void expectInView(const hdhair::CameraPrim& camera, const std::vector<Float3>& points) {
    const glm::dmat4 worldToCamera = glm::inverse(camera.worldTransform);
    const double tanX = camera.horizontalAperture / 2 / camera.focalLength,
                 tanY = camera.verticalAperture / 2 / camera.focalLength;
    for (const Float3& p : points) {
        const glm::dvec4 c = worldToCamera * glm::dvec4(p.x, p.y, p.z, 1.0);
        const double depth = -c.z;
        ASSERT_GT(depth, camera.clippingRange.x) << p.x << " " << p.y << " " << p.z;
        ASSERT_LT(depth, camera.clippingRange.y);
        EXPECT_LE(std::abs(c.x) / depth, tanX * 0.86);
        EXPECT_LE(std::abs(c.y) / depth, tanY * 0.86);
    }
}

// ---------------------------------------------------------------------------
// TressFX

TEST_F(HairImport, TressFx40PositionsWithoutW) {
    const HairStrands s = readTressFx(write("four.tfx", tfx40(2, 3)));
    EXPECT_EQ(s.source, "four.tfx");
    EXPECT_EQ(s.format, "TressFX 4.0");
    EXPECT_EQ(s.vertexCounts, (std::vector<int>{3, 3}));
    ASSERT_EQ(s.points.size(), 6u);
    for (uint32_t i = 0; i < 6; ++i) expectPoint(s.points[i], syntheticPoint(i / 3, i % 3));
    EXPECT_TRUE(s.strandThickness.empty());
    EXPECT_TRUE(s.widths.empty());
}

TEST_F(HairImport, TressFx40StrandThickness) {
    const HairStrands s = readTressFx(write("thick.tfx", tfx40(2, 4, true)));
    EXPECT_EQ(s.strandThickness, (std::vector<float>{0.5f, 0.75f}));
    expectPoint(s.points[7], syntheticPoint(1, 3));
}

TEST_F(HairImport, TressFx30Positions) {
    const HairStrands s = readTressFx(write("three.tfx", tfx30(3, 4)));
    EXPECT_EQ(s.format, "TressFX 3.0");
    EXPECT_EQ(s.vertexCounts, (std::vector<int>{4, 4, 4}));
    ASSERT_EQ(s.points.size(), 12u);
    for (uint32_t i = 0; i < 12; ++i) expectPoint(s.points[i], syntheticPoint(i / 4, i % 4));
}

TEST_F(HairImport, TressFxTruncatedFilesNameWhatIsMissing) {
    Bytes b40 = tfx40(2, 3);  // 160 + 96 bytes
    b40.data.resize(200);
    EXPECT_EQ(errorOf([&] { readTressFx(write("short40.tfx", b40)); }),
              "short40.tfx: positions (2 strands x 3 vertices x 16 bytes) at byte 160 run past the end of the "
              "200-byte file (they end at byte 256)");
    Bytes b30 = tfx30(2, 3);  // 296 + 72 bytes
    b30.data.resize(367);
    EXPECT_EQ(errorOf([&] { readTressFx(write("short30.tfx", b30)); }),
              "short30.tfx: positions (2 strands x 3 vertices x 12 bytes) at byte 296 run past the end of the "
              "367-byte file (they end at byte 368)");
    Bytes header = tfx40(2, 3);
    header.data.resize(100);
    EXPECT_EQ(errorOf([&] { readTressFx(write("header.tfx", header)); }),
              "header.tfx: the 100-byte file is too small for a TressFX 4.0 header (160 bytes)");
    Bytes header30 = tfx30(2, 3);
    header30.data.resize(140);
    EXPECT_EQ(errorOf([&] { readTressFx(write("header30.tfx", header30)); }),
              "header30.tfx: the 140-byte file is too small for a TressFX 3.0 header (at least 148 bytes)");
    EXPECT_EQ(errorOf([&] { readTressFx(write("tiny.tfx", std::vector<uint8_t>{0, 0, 128, 64})); }),
              "tiny.tfx: the 4-byte file is too small for a TressFX header");
    Bytes thick = tfx40(2, 3, true);
    thick.data.resize(thick.size() - 1);
    EXPECT_EQ(errorOf([&] { readTressFx(write("thick.tfx", thick)); }),
              "thick.tfx: strand thicknesses (2 strands x 4 bytes) at byte 256 run past the end of the 263-byte "
              "file (they end at byte 264)");
}

TEST_F(HairImport, TressFxCorruptHeadersAreRejected) {
    auto patched = [&](Bytes b, size_t at, uint32_t value) {
        std::memcpy(b.data.data() + at, &value, 4);
        return b;
    };
    auto patchedFloat = [&](Bytes b, size_t at, float value) {
        std::memcpy(b.data.data() + at, &value, 4);
        return b;
    };
    EXPECT_EQ(errorOf([&] { readTressFx(write("v.tfx", patchedFloat(tfx40(1, 2), 0, 2.5f))); }),
              "v.tfx: unsupported TressFX version 2.5 (the first 4 bytes; 3.0 and 4.0 are read)");
    EXPECT_EQ(errorOf([&] { readTressFx(write("zero.tfx", patched(tfx40(1, 2), 4, 0))); }),
              "zero.tfx: the header says the file has 0 strands");
    EXPECT_EQ(errorOf([&] { readTressFx(write("one.tfx", patched(tfx30(2, 2), 8, 1))); }),
              "one.tfx: the header says 1 vertices per strand (a strand needs at least 2)");
    EXPECT_EQ(errorOf([&] { readTressFx(write("huge.tfx", patched(tfx40(2, 3), 4, 4000000000u))); }),
              "huge.tfx: positions (4000000000 strands x 3 vertices x 16 bytes) at byte 160 run past the end of "
              "the 256-byte file (they end at byte 192000000160)");
    EXPECT_EQ(errorOf([&] { readTressFx(write("overlap.tfx", patched(tfx40(2, 3), 12, 64))); }),
              "overlap.tfx: positions (2 strands x 3 vertices x 16 bytes) at byte 64 overlap the 160-byte header");
    EXPECT_EQ(errorOf([&] { readTressFx(write("nopos.tfx", patched(tfx40(2, 3), 12, 0))); }),
              "nopos.tfx: the header has no positions (offsetVertexPosition is 0)");
    EXPECT_EQ(errorOf([&] { readTressFx(write("far.tfx", patched(tfx30(2, 3), 144, 1u << 30))); }),
              "far.tfx: positions (2 strands x 3 vertices x 12 bytes) at byte 1073741824 run past the end of the "
              "368-byte file (they end at byte 1073741896)");
    EXPECT_EQ(errorOf([&] { readTressFx(write("uv.tfx", patched(tfx40(2, 3), 16, 250))); }),
              "uv.tfx: strand UVs (2 strands x 8 bytes) at byte 250 run past the end of the 256-byte file (they "
              "end at byte 266)");
    EXPECT_EQ(errorOf([&] { readTressFx(write("nan.tfx", patchedFloat(tfx40(2, 3), 160 + 16, std::nanf("")))); }),
              "nan.tfx: vertex 1 of strand 0 (byte 176) is not finite: (nan, 8.5, 0.25)");
    EXPECT_EQ(errorOf([&] { readTressFx((dir_ / "missing.tfx").string()); }),
              "missing.tfx: cannot open (No such file or directory)");
}

// ---------------------------------------------------------------------------
// Cem Yuksel's .hair

TEST_F(HairImport, YukselHairEveryArray) {
    const HairStrands s = readYukselHair(write("full.hair", HairFile{}.bytes()));
    EXPECT_EQ(s.format, "Cem Yuksel .hair");
    EXPECT_EQ(s.vertexCounts, (std::vector<int>{3, 2}));
    ASSERT_EQ(s.points.size(), 5u);
    ASSERT_EQ(s.widths.size(), 5u);
    ASSERT_EQ(s.opacities.size(), 5u);
    ASSERT_EQ(s.colors.size(), 5u);
    for (uint32_t i = 0; i < 5; ++i) {
        expectPoint(s.points[i], HairFile::point(i));
        EXPECT_FLOAT_EQ(s.widths[i], HairFile::thickness(i));
        EXPECT_FLOAT_EQ(s.opacities[i], 1.0f - HairFile::transparency(i));
        expectPoint(s.colors[i], HairFile::color(i));
    }
    EXPECT_FALSE(s.defaultWidth || s.defaultOpacity || s.defaultColor);
}

TEST_F(HairImport, YukselHairHeaderDefaults) {
    HairFile file;
    file.arrays = 0x2;  // points only
    file.segments = {0, 0, 0};
    file.defaultSegments = 3;
    const HairStrands s = readYukselHair(write("defaults.hair", file.bytes()));
    EXPECT_EQ(s.vertexCounts, (std::vector<int>{4, 4, 4}));
    EXPECT_EQ(s.points.size(), 12u);
    EXPECT_TRUE(s.widths.empty() && s.colors.empty() && s.opacities.empty());
    ASSERT_TRUE(s.defaultWidth && s.defaultOpacity && s.defaultColor);
    EXPECT_FLOAT_EQ(*s.defaultWidth, 0.5f);
    EXPECT_FLOAT_EQ(*s.defaultOpacity, 0.75f);
    expectPoint(*s.defaultColor, {0.1f, 0.2f, 0.3f});

    file.defaultThickness = 0.0f;
    file.defaultTransparency = 0.0f;
    file.defaultColor = {0, 0, 0};
    const HairStrands unset = readYukselHair(write("unset.hair", file.bytes()));
    EXPECT_FALSE(unset.defaultWidth || unset.defaultOpacity || unset.defaultColor);
}

TEST_F(HairImport, YukselHairErrors) {
    Bytes magic = HairFile{}.bytes();
    magic.data[0] = 'X';
    EXPECT_EQ(errorOf([&] { readYukselHair(write("magic.hair", magic)); }),
              "magic.hair: not a .hair file (the first 4 bytes are not \"HAIR\")");
    HairFile noPoints;
    noPoints.arrays = 0x1d;
    EXPECT_EQ(errorOf([&] { readYukselHair(write("nopoints.hair", noPoints.bytes())); }),
              "nopoints.hair: the file has no points array (bit 1 of the array bit field is 0)");
    HairFile count;
    count.pointCountAdjust = 1;
    EXPECT_EQ(errorOf([&] { readYukselHair(write("count.hair", count.bytes())); }),
              "count.hair: the header says 6 points but the 2 hairs' segments need 5");
    HairFile zero;
    zero.segments = {2, 0};
    EXPECT_EQ(errorOf([&] { readYukselHair(write("zero.hair", zero.bytes())); }), "zero.hair: hair 1 has 0 segments");
    // 128 header + 4 segments + 60 points + 20 thickness + 20 transparency = 232; colours need 60 more.
    Bytes truncated = HairFile{}.bytes();
    truncated.data.resize(250);
    EXPECT_EQ(errorOf([&] { readYukselHair(write("short.hair", truncated)); }),
              "short.hair: colors (5 x 12 bytes) at byte 232 run past the end of the 250-byte file (they end at "
              "byte 292)");
    Bytes header = HairFile{}.bytes();
    header.data.resize(127);
    EXPECT_EQ(errorOf([&] { readYukselHair(write("header.hair", header)); }),
              "header.hair: the 127-byte file is too small for a .hair header (128 bytes)");
}

// Transparencies beyond [0, 1] and negative colours are clamped, each array
// noting one repair the converter prints.
TEST_F(HairImport, YukselOutOfRangeOpacityAndColourAreClampedAndNoted) {
    Bytes file = HairFile{}.bytes();
    // 128 header + 4 segments + 60 points + 20 thickness: transparency of point 1, then colour of point 0.
    const float transparency = 1.5f, red = -0.25f;
    std::memcpy(file.data.data() + 128 + 4 + 60 + 20 + 4, &transparency, 4);
    std::memcpy(file.data.data() + 128 + 4 + 60 + 20 + 20, &red, 4);
    const HairStrands s = readYukselHair(write("range.hair", file));
    EXPECT_FLOAT_EQ(s.opacities[1], 0.0f);
    EXPECT_FLOAT_EQ(s.colors[0].x, 0.0f);
    EXPECT_FLOAT_EQ(s.colors[0].y, HairFile::color(0).y);
    EXPECT_EQ(s.repairs, (std::vector<std::string>{"1 transparency value(s) outside [0, 1] (e.g. 1.5); clamped",
                                                   "1 colour component value(s) outside [0, inf] (e.g. -0.25); clamped"}));
    EXPECT_TRUE(readYukselHair(write("fine.hair", HairFile{}.bytes())).repairs.empty());
}

// A header's counts are checked against the bytes present before anything
// is sized by them: four billion hairs in a 192-byte file (16 GB of vertex
// counts, had they been allocated first) is a one-line error.
TEST_F(HairImport, YukselHeaderCountsAreCheckedBeforeAllocating) {
    Bytes huge = HairFile{}.bytes();
    huge.data.resize(192);
    const uint32_t hairs = 4000000000u;
    std::memcpy(huge.data.data() + 4, &hairs, sizeof hairs);
    EXPECT_EQ(errorOf([&] { readYukselHair(write("huge.hair", huge)); }),
              "huge.hair: segment counts (4000000000 x 2 bytes) at byte 128 run past the end of the 192-byte file "
              "(they end at byte 8000000128)");
    HairFile noSegments;
    noSegments.arrays = 0x2;  // points only: the default segment count sizes every hair
    noSegments.segments = {0, 0};
    noSegments.defaultSegments = 3;
    Bytes manyDefaults = noSegments.bytes();
    std::memcpy(manyDefaults.data.data() + 4, &hairs, sizeof hairs);
    EXPECT_EQ(errorOf([&] { readYukselHair(write("defaults.hair", manyDefaults)); }),
              "defaults.hair: the header says 8 points but the 4000000000 hairs' segments need 16000000000");
}

// Only regular files are read: a device would never end, a FIFO would block.
TEST_F(HairImport, OnlyRegularFilesAreRead) {
    EXPECT_EQ(errorOf([&] { readTressFx("/dev/zero"); }), "zero: cannot open (a character device, not a regular file)");
    EXPECT_EQ(errorOf([&] { readYukselHair("/dev/zero"); }),
              "zero: cannot open (a character device, not a regular file)");
    const std::string fifo = (dir_ / "pipe.hair").string();
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    EXPECT_EQ(errorOf([&] { readYukselHair(fifo); }), "pipe.hair: cannot open (a FIFO, not a regular file)");
    EXPECT_EQ(errorOf([&] { readTressFx(dir_.string()); }),
              dir_.filename().string() + ": cannot open (a directory, not a regular file)");
}

// ---------------------------------------------------------------------------
// Writer

TEST_F(HairImport, NumbersAndNames) {
    EXPECT_EQ(formatNumber(0.1), "0.1");
    EXPECT_EQ(formatNumber(100), "100");
    EXPECT_EQ(formatNumber(-2.5), "-2.5");
    EXPECT_EQ(formatNumber(0.30000001192092896), "0.3");
    EXPECT_EQ(formatNumber(1234567.0), "1234570");
    EXPECT_EQ(formatNumber(0.000015), "0.000015");
    EXPECT_EQ(formatNumber(1.23456789e-5), "0.0000123457");
    EXPECT_EQ(formatNumber(1e-7), "0");
    EXPECT_EQ(formatNumber(-0.0), "0");
    EXPECT_EQ(usdIdentifier("Ratboy_mohawk"), "Ratboy_mohawk");
    EXPECT_EQ(usdIdentifier("front top-2.v1"), "front_top_2_v1");
    EXPECT_EQ(usdIdentifier("1hair"), "_1hair");
    EXPECT_EQ(usdIdentifier(""), "hair");
}

TEST_F(HairImport, WrittenStageReadsBack) {
    UsdaWriteOptions options;
    options.doc = "a \"quoted\" doc";
    const CurvesUsda usda = buildCurvesUsda({{"two", twoStrands()}}, options);
    EXPECT_EQ(usda.text.rfind("#usda 1.0\n(\n    doc = \"a \\\"quoted\\\" doc\"\n    defaultPrim = \"World\"\n", 0), 0u)
        << usda.text.substr(0, 200);
    auto r = readBack(usda.text);
    EXPECT_EQ(r->stage->info().defaultPrim, "World");
    EXPECT_EQ(r->stage->info().upAxis, "Y");
    EXPECT_DOUBLE_EQ(r->stage->info().metersPerUnit, 0.01);
    EXPECT_TRUE(r->diagnostics.warnings().empty());
    const hdhair::CurvesPrim* curves = r->scene.findCurves("/World/two");
    ASSERT_NE(curves, nullptr);
    EXPECT_EQ(curves->type, hdhair::CurveType::Cubic);
    EXPECT_EQ(curves->basis, hdhair::CurveBasis::CatmullRom);
    EXPECT_EQ(curves->wrap, hdhair::CurveWrap::Pinned);
    EXPECT_EQ(curves->curveVertexCounts, (std::vector<int>{3, 4}));
    const HairStrands s = twoStrands();
    ASSERT_EQ(curves->points.size(), s.points.size());
    for (size_t i = 0; i < s.points.size(); ++i)
        EXPECT_EQ(curves->points[i], glm::vec3(s.points[i].x, s.points[i].y, s.points[i].z));

    // Automatic taper: root 0.0015 x the bounds' diagonal, tip 0.2 x root.
    const float diagonal = std::sqrt(6.0f * 6 + 10 * 10 + 3 * 3);
    const float root = 0.0015f * diagonal, tip = 0.2f * root;
    EXPECT_FLOAT_EQ(usda.rootWidth, root);
    const hdhair::Primvar* widths = curves->findPrimvar("widths");
    ASSERT_NE(widths, nullptr);
    EXPECT_EQ(widths->interpolation, hdhair::Interpolation::Vertex);
    const std::vector<float> expected = {root, (root + tip) / 2, tip, root, root + (tip - root) / 3,
                                         root + 2 * (tip - root) / 3, tip};
    ASSERT_EQ(widths->values.size(), expected.size());
    for (size_t i = 0; i < expected.size(); ++i) EXPECT_NEAR(widths->values[i], expected[i], 1e-6f * root * 10);

    const hdhair::Primvar* color = curves->findPrimvar("displayColor");
    ASSERT_NE(color, nullptr);
    EXPECT_EQ(color->interpolation, hdhair::Interpolation::Constant);
    EXPECT_EQ(color->values, (std::vector<float>{0.4f, 0.22f, 0.1f}));
    EXPECT_EQ(curves->findPrimvar("displayOpacity"), nullptr);

    const hdhair::usda::Prim* prim = r->stage->findPrim("/World/two");
    ASSERT_NE(prim, nullptr);
    ASSERT_NE(prim->attribute("extent"), nullptr);

    const hdhair::CameraPrim* camera = r->scene.findCamera("/World/main_cam");
    ASSERT_NE(camera, nullptr);
    EXPECT_FLOAT_EQ(camera->focalLength, 50.0f);
    EXPECT_FLOAT_EQ(camera->horizontalAperture, 20.955f);
    EXPECT_FLOAT_EQ(camera->verticalAperture, 15.2908f);
    expectInView(*camera, s.points);
    // From +Z: the camera's -Z looks along -Z.
    const glm::dvec3 forward = -glm::dvec3(camera->worldTransform[2]);
    EXPECT_NEAR(forward.z, -1.0, 1e-6);

    ASSERT_EQ(r->scene.lights().size(), 1u);
    const hdhair::LightPrim& light = *r->scene.lights().at("/World/key_light").prim;
    EXPECT_EQ(light.type, hdhair::LightType::Distant);
    EXPECT_FLOAT_EQ(light.intensity, 2.0f);
    const glm::dvec3 travel = -glm::dvec3(light.worldTransform[2]);
    EXPECT_LT(travel.y, -0.5);  // from above
    EXPECT_LT(travel.z, -0.3);  // from the front
}

TEST_F(HairImport, WidthOptionsColorAndNoCamera) {
    UsdaWriteOptions options;
    options.rootWidth = 0.5f;
    options.tipWidth = 0.1f;
    options.color = Float3{0.9f, 0.8f, 0.7f};
    options.camera = false;
    options.metersPerUnit = 1.0;
    options.upAxis = 'Z';
    HairStrands thick = twoStrands();
    thick.strandThickness = {1.0f, 2.0f};
    auto r = readBack(buildCurvesUsda({{"two", thick}}, options).text);
    EXPECT_EQ(r->stage->info().upAxis, "Z");
    EXPECT_DOUBLE_EQ(r->stage->info().metersPerUnit, 1.0);
    EXPECT_TRUE(r->scene.cameras().empty());
    EXPECT_TRUE(r->scene.lights().empty());
    const hdhair::CurvesPrim* curves = r->scene.findCurves("/World/two");
    ASSERT_NE(curves, nullptr);
    const std::vector<float> expected = {0.5f, 0.3f, 0.1f, 1.0f, 1.0f - 0.8f / 3, 1.0f - 1.6f / 3, 0.2f};
    const std::vector<float>& widths = curves->findPrimvar("widths")->values;
    ASSERT_EQ(widths.size(), expected.size());
    for (size_t i = 0; i < expected.size(); ++i) EXPECT_NEAR(widths[i], expected[i], 1e-6f);
    EXPECT_EQ(curves->findPrimvar("displayColor")->values, (std::vector<float>{0.9f, 0.8f, 0.7f}));

    options.rootWidth.reset();  // tip only: the root is automatic
    const CurvesUsda tipOnly = buildCurvesUsda({{"two", twoStrands()}}, options);
    EXPECT_FLOAT_EQ(tipOnly.tipWidth, 0.1f);
    EXPECT_GT(tipOnly.rootWidth, 0.0f);

    options.rootWidth = -1.0f;
    EXPECT_THROW(buildCurvesUsda({{"two", twoStrands()}}, options), std::invalid_argument);
    options.rootWidth.reset();
    options.upAxis = 'X';
    EXPECT_THROW(buildCurvesUsda({{"two", twoStrands()}}, options), std::invalid_argument);
    EXPECT_THROW(buildCurvesUsda({}, UsdaWriteOptions{}), std::invalid_argument);
    HairStrands bad = twoStrands();
    bad.vertexCounts[0] = 1;
    bad.vertexCounts[1] = 6;
    EXPECT_THROW(buildCurvesUsda({{"bad", bad}}, UsdaWriteOptions{}), std::invalid_argument);
}

TEST_F(HairImport, CameraFramesFromAnyDirection) {
    const HairStrands s = twoStrands();
    struct Case {
        char up;
        std::optional<Float3> from;
    };
    for (const Case& c : {Case{'Y', std::nullopt}, Case{'Z', std::nullopt}, Case{'Y', Float3{1, 1, 1}},
                          Case{'Y', Float3{0, 1, 0}}, Case{'Z', Float3{0, 0, -1}}, Case{'Y', Float3{-3, 0.2f, -1}}}) {
        UsdaWriteOptions options;
        options.upAxis = c.up;
        options.cameraFrom = c.from;
        auto r = readBack(buildCurvesUsda({{"two", s}}, options).text);
        const hdhair::CameraPrim* camera = r->scene.findCamera("/World/main_cam");
        ASSERT_NE(camera, nullptr);
        SCOPED_TRACE(std::string(1, c.up) + (c.from ? " from given" : " default"));
        expectInView(*camera, s.points);
        if (c.up == 'Z' && !c.from) {
            // Default for Z up: from -Y, +Z up in the image.
            EXPECT_NEAR(glm::dvec3(camera->worldTransform[2]).y, -1.0, 1e-6);
            EXPECT_NEAR(glm::dvec3(camera->worldTransform[1]).z, 1.0, 1e-6);
        }
        if (c.from && c.from->y == 0 && c.up == 'Y') {
            EXPECT_NEAR(glm::dvec3(camera->worldTransform[0]).y, 0.0, 1e-5);  // no roll
        }
    }
}

TEST_F(HairImport, HairAttributesAndMergedInputs) {
    HairFile file;
    const HairStrands hair = readYukselHair(write("full.hair", file.bytes()));
    auto usda = buildCurvesUsda({{"a b", hair}, {"a-b", twoStrands()}, {"main_cam", twoStrands()}}, {});
    auto r = readBack(usda.text);
    ASSERT_EQ(usda.curves.size(), 3u);
    EXPECT_EQ(usda.curves[0].path, "/World/a_b");
    EXPECT_EQ(usda.curves[1].path, "/World/a_b_2");
    EXPECT_EQ(usda.curves[2].path, "/World/main_cam_2");
    EXPECT_EQ(r->scene.curves().size(), 3u);
    const hdhair::CurvesPrim* curves = r->scene.findCurves("/World/a_b");
    ASSERT_NE(curves, nullptr);
    EXPECT_EQ(curves->curveVertexCounts, (std::vector<int>{3, 2}));
    const hdhair::Primvar* widths = curves->findPrimvar("widths");
    const hdhair::Primvar* colors = curves->findPrimvar("displayColor");
    const hdhair::Primvar* opacity = curves->findPrimvar("displayOpacity");
    ASSERT_TRUE(widths && colors && opacity);
    EXPECT_EQ(widths->interpolation, hdhair::Interpolation::Vertex);
    EXPECT_EQ(colors->interpolation, hdhair::Interpolation::Vertex);
    EXPECT_EQ(opacity->interpolation, hdhair::Interpolation::Vertex);
    ASSERT_EQ(widths->values.size(), 5u);
    ASSERT_EQ(colors->values.size(), 15u);
    for (uint32_t i = 0; i < 5; ++i) {
        EXPECT_NEAR(widths->values[i], HairFile::thickness(i), 1e-6f);
        EXPECT_NEAR(opacity->values[i], 1.0f - HairFile::transparency(i), 1e-6f);
        EXPECT_NEAR(colors->values[i * 3 + 2], HairFile::color(i).z, 1e-6f);
    }
    // The other inputs keep the automatic taper.
    EXPECT_EQ(r->scene.findCurves("/World/a_b_2")->findPrimvar("widths")->values.size(), 7u);

    // Header defaults: one constant width, colour and opacity.
    file.arrays = 0x3;
    auto d = readBack(buildCurvesUsda({{"d", readYukselHair(write("d.hair", file.bytes()))}}, {}).text);
    const hdhair::CurvesPrim* dc = d->scene.findCurves("/World/d");
    ASSERT_NE(dc, nullptr);
    EXPECT_EQ(dc->findPrimvar("widths")->values, (std::vector<float>{0.5f}));
    EXPECT_EQ(dc->findPrimvar("widths")->interpolation, hdhair::Interpolation::Constant);
    EXPECT_EQ(dc->findPrimvar("displayColor")->values, (std::vector<float>{0.1f, 0.2f, 0.3f}));
    EXPECT_EQ(dc->findPrimvar("displayOpacity")->values, (std::vector<float>{0.75f}));
}

TEST_F(HairImport, AtomicFileWriteAndReadSceneFile) {
    const std::string path = (dir_ / "out.usda").string();
    writeFileAtomically(path, buildCurvesUsda({{"two", twoStrands()}}, {}).text);
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_)) names.push_back(entry.path().filename().string());
    EXPECT_EQ(names, (std::vector<std::string>{"out.usda"}));  // no temporary file left behind
    hdhair::Scene scene;
    hdhair::Diagnostics diagnostics;
    auto stage = hdhair::usda::readSceneFile(path, 0.0, scene, diagnostics);
    ASSERT_NE(scene.findCurves("/World/two"), nullptr);
    EXPECT_EQ(scene.findCurves("/World/two")->points.size(), 7u);
    EXPECT_THROW(writeFileAtomically((dir_ / "no/such/dir/out.usda").string(), "x"), std::runtime_error);
}

TEST_F(HairImport, SubsampleAndFollowStrands) {
    HairStrands ten;
    for (int s = 0; s < 10; ++s) {
        ten.vertexCounts.push_back(2 + s % 4);
        for (int v = 0; v < 2 + s % 4; ++v) {
            ten.points.push_back({float(s), float(-v), 0});
            ten.widths.push_back(float(s));
        }
    }
    const HairStrands three = subsampleStrands(ten, 3);
    EXPECT_EQ(three.vertexCounts, (std::vector<int>{2, 5, 4}));  // strands 0, 3, 6
    ASSERT_EQ(three.points.size(), 11u);
    ASSERT_EQ(three.widths.size(), 11u);
    EXPECT_EQ(three.points[2].x, 3.0f);
    EXPECT_EQ(three.points[7].x, 6.0f);
    EXPECT_EQ(three.widths[10], 6.0f);
    EXPECT_EQ(subsampleStrands(ten, 50).strandCount(), 10u);

    FollowOptions follow;
    follow.perGuide = 3;
    follow.radius = 0.2f;
    follow.tipSeparation = 1.0f;
    const HairStrands guides = twoStrands();
    const HairStrands grown = addFollowStrands(guides, follow);
    EXPECT_EQ(grown.vertexCounts, (std::vector<int>{3, 3, 3, 3, 4, 4, 4, 4}));
    ASSERT_EQ(grown.points.size(), 4 * guides.points.size());
    for (int i = 0; i < 3; ++i) expectPoint(grown.points[size_t(i)], guides.points[size_t(i)]);
    for (int i = 0; i < 4; ++i) expectPoint(grown.points[12 + size_t(i)], guides.points[3 + size_t(i)]);
    for (size_t copy = 1; copy < 4; ++copy) {
        const Float3 root = grown.points[copy * 3], guideRoot = guides.points[0];
        const glm::vec3 offset(root.x - guideRoot.x, root.y - guideRoot.y, root.z - guideRoot.z);
        const glm::vec3 tangent = glm::normalize(glm::vec3(0, -5, 1));
        EXPECT_LE(glm::length(offset), 0.2f + 1e-5f);
        EXPECT_GT(glm::length(offset), 0.0f);
        EXPECT_NEAR(glm::dot(offset, tangent), 0.0f, 1e-5f);  // perpendicular at the root
        const Float3 tip = grown.points[copy * 3 + 2], guideTip = guides.points[2];
        const float tipOffset = glm::length(glm::vec3(tip.x - guideTip.x, tip.y - guideTip.y, tip.z - guideTip.z));
        EXPECT_NEAR(tipOffset, 2.0f * glm::length(offset), 1e-4f);  // (1 + tipSeparation) x at the tip
    }
    const HairStrands again = addFollowStrands(guides, follow);
    for (size_t i = 0; i < grown.points.size(); ++i) expectPoint(again.points[i], grown.points[i]);  // deterministic
    follow.perGuide = -1;
    EXPECT_THROW(addFollowStrands(guides, follow), std::invalid_argument);
}

// ---------------------------------------------------------------------------
// AMD's TressFX samples (../shared/data/tressfx), when present

// The counts a .tfx header states, read independently of the reader.
std::pair<uint32_t, uint32_t> headerCounts(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    uint32_t words[3] = {};
    in.read(reinterpret_cast<char*>(words), sizeof words);
    return {words[1], words[2]};
}

// A tiny .obj (a quad and a triangle, one object, one group, relative and
// v/vt/vn indices) becomes a Mesh prim beside the hair, in the same space,
// with its faces as authored; the camera frames hair and mesh together.
TEST_F(HairImport, ObjMeshesBecomeMeshPrims) {
    const std::string obj = "# two faces\no head\nv 0 0 0\nv 2 0 0\nv 2 2 0\nv 0 2 0\nv 1 3 -1\n"
                            "vt 0 0\nvn 0 0 1\ng skin\ns 1\nf 1/1/1 2/1/1 3/1/1 4/1/1\nf -2 -3 -1\n";
    const std::string path = write("head.obj", std::vector<uint8_t>(obj.begin(), obj.end()));
    const PolygonMesh mesh = readObjMesh(path);
    EXPECT_EQ(mesh.faceVertexCounts, (std::vector<int>{4, 3}));
    EXPECT_EQ(mesh.faceVertexIndices, (std::vector<int>{0, 1, 2, 3, 3, 2, 4}));
    ASSERT_EQ(mesh.points.size(), 5u);
    expectPoint(mesh.points[4], {1, 3, -1});

    MeshInput head;
    head.name = "head";
    head.mesh = mesh;
    head.subdivisionScheme = "catmullClark";
    const CurvesUsda usda = buildCurvesUsda({{"two", twoStrands()}}, {}, {head});
    ASSERT_EQ(usda.meshes.size(), 1u);
    EXPECT_EQ(usda.meshes[0].path, "/World/head");
    auto r = readBack(usda.text);
    EXPECT_EQ(r->diagnostics.warningCount(), 0u);
    ASSERT_EQ(r->scene.meshes().count("/World/head"), 1u);
    const hdhair::MeshPrim& prim = *r->scene.meshes().at("/World/head").prim;
    EXPECT_EQ(prim.faceVertexCounts, mesh.faceVertexCounts);
    EXPECT_EQ(prim.faceVertexIndices, mesh.faceVertexIndices);
    EXPECT_EQ(prim.subdivisionScheme, "catmullClark");
    EXPECT_EQ(prim.worldTransform, glm::dmat4(1.0));
    ASSERT_EQ(prim.points.size(), 5u);
    EXPECT_EQ(prim.points[2], glm::vec3(2, 2, 0));
    ASSERT_NE(prim.findPrimvar("displayColor"), nullptr);
    EXPECT_EQ(prim.findPrimvar("displayColor")->values, (std::vector<float>{0.72f, 0.56f, 0.48f}));
    std::vector<Float3> everything = twoStrands().points;
    everything.insert(everything.end(), mesh.points.begin(), mesh.points.end());
    expectInView(*r->scene.findCamera("/World/main_cam"), everything);
    // Default: the polygons as authored.
    head.subdivisionScheme = "none";
    auto plain = readBack(buildCurvesUsda({}, {}, {head}).text);
    EXPECT_EQ(plain->scene.meshes().at("/World/head").prim->subdivisionScheme, "none");
    EXPECT_TRUE(plain->scene.curves().empty());
}

TEST_F(HairImport, MalformedObjFilesNameTheFileAndTheProblem) {
    auto objError = [&](const std::string& name, const std::string& text) {
        const std::string path = write(name, std::vector<uint8_t>(text.begin(), text.end()));
        try {
            readObjMesh(path);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what()).substr(path.size());
        }
        return std::string("no error");
    };
    EXPECT_EQ(objError("far.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"),
              ": face 1 of '' names vertex 9, outside the 3 vertices");
    EXPECT_EQ(objError("empty.obj", "v 0 0 0\n"), ": no faces");
    const std::string missing = (dir_ / "nothere.obj").string();
    try {
        readObjMesh(missing);
        ADD_FAILURE() << "a missing file was read";
    } catch (const std::invalid_argument& e) {
        EXPECT_EQ(std::string(e.what()).rfind(missing + ": ", 0), 0u) << e.what();
    }
    MeshInput bad;
    bad.name = "bad";
    bad.mesh.source = "bad.obj";
    bad.mesh.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    bad.mesh.faceVertexCounts = {3};
    bad.mesh.faceVertexIndices = {0, 1, 2};
    bad.subdivisionScheme = "butterfly";
    try {
        buildCurvesUsda({}, {}, {bad});
        ADD_FAILURE() << "an unknown scheme was written";
    } catch (const std::invalid_argument& e) {
        EXPECT_EQ(std::string(e.what()),
                  "bad.obj: unknown subdivision scheme 'butterfly' (catmullClark, loop, bilinear or none)");
    }
}

TEST_F(HairImport, RealTressFxAssets) {
    const fs::path root = fs::path(HDHAIR_SHARED_DATA_DIR) / "tressfx";
    if (!fs::is_directory(root)) GTEST_SKIP() << "no shared data at " << root.string() << " (see data/README.md)";
    struct Asset {
        const char* path;
        const char* format;
        uint32_t strands, vertices;
    };
    // Counts as the files' headers state them (../shared/data/README.md agrees).
    const Asset assets[] = {{"ratboy/Ratboy_mohawk.tfx", "TressFX 4.0", 2226, 32},
                            {"sintel/sintel_hair.tfx", "TressFX 4.0", 228, 32},
                            {"bear/bear.tfx", "TressFX 3.0", 48113, 4},
                            {"ponytail/tail.tfx", "TressFX 3.0", 474, 16},
                            {"testhair1/TestHair1.tfx", "TressFX 3.0", 10027, 4}};
    for (const Asset& asset : assets) {
        const std::string path = (root / asset.path).string();
        if (!fs::exists(path)) {
            ADD_FAILURE() << path << " is missing from the shared data";
            continue;
        }
        SCOPED_TRACE(path);
        EXPECT_EQ(headerCounts(path), std::make_pair(asset.strands, asset.vertices));
        const HairStrands s = readTressFx(path);
        EXPECT_EQ(s.format, asset.format);
        ASSERT_EQ(s.strandCount(), asset.strands);
        EXPECT_EQ(s.vertexCounts.front(), int(asset.vertices));
        EXPECT_EQ(s.pointCount(), size_t{asset.strands} * asset.vertices);
    }

    // Ratboy, converted and read back: every strand and point, with the camera framing them.
    const HairStrands ratboy = readTressFx((root / "ratboy/Ratboy_mohawk.tfx").string());
    expectPoint(ratboy.points.front(), {0.8735438585281372f, 81.22692108154297f, 0.6029660701751709f});
    auto r = readBack(buildCurvesUsda({{"Ratboy_mohawk", ratboy}}, {}).text);
    const hdhair::CurvesPrim* curves = r->scene.findCurves("/World/Ratboy_mohawk");
    ASSERT_NE(curves, nullptr);
    EXPECT_EQ(curves->curveVertexCounts, std::vector<int>(2226, 32));
    EXPECT_EQ(curves->points.size(), 2226u * 32u);
    EXPECT_EQ(curves->findPrimvar("widths")->values.size(), 2226u * 32u);
    expectInView(*r->scene.findCamera("/World/main_cam"), ratboy.points);
}

}  // namespace
