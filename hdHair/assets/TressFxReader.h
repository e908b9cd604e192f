#pragma once
// Reads AMD TressFX .tfx hair assets (format versions 3.0 and 4.0) into
// HairStrands, the pxr-free strand list every hair reader in this folder
// produces and UsdaCurvesWriter.h writes. See tools/README.md "Converting hair
// assets" and ../shared/data/README.md.
//
// Format (little-endian, 32-bit fields):
//  - 4.0: a 160-byte header: float version (4.0), uint numHairStrands,
//    uint numVerticesPerStrand, then byte offsets from the start of the file
//    (0 = absent): offsetVertexPosition, offsetStrandUV, offsetVertexUV,
//    offsetStrandThickness, offsetVertexColor, then 32 reserved words.
//    Positions are float4 per vertex; w flags a pinned (0) or movable (1)
//    vertex and is not a coordinate, so it is dropped. Strand UVs are float2
//    per strand, vertex UVs float2 per vertex, strand thickness one float per
//    strand (kept as HairStrands::strandThickness), vertex colours float4 per
//    vertex; each present array must lie inside the file.
//  - 3.0: float version (3.0), uint numGuideHairStrands,
//    uint numVerticesPerStrand; the word at index 36 (byte 144) is the byte
//    offset of the positions (296 in AMD's samples), float3 per vertex.
//    Nothing else is read from a 3.0 file.
// Strands are stored one after another, root first, every strand with the
// same vertex count.
//
// Validation: every header field that locates or sizes data is checked
// against the file size before anything is read (version, strand and vertex
// counts, offsets past the header and inside the file); positions must be
// finite. Errors throw std::runtime_error with one line that starts with the
// file's name: "Ratboy_mohawk.tfx: positions (2226 strands x 32 vertices x 16
// bytes) at byte 160 run past the end of the 12288-byte file (they end at
// byte 1139872)".

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace hdhair::convert {

struct Float3 {
    float x = 0.0f, y = 0.0f, z = 0.0f;
};

inline bool operator==(const Float3& a, const Float3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

// Hair strands as a file stores them, in the file's units and axes.
struct HairStrands {
    std::string source;               // the file's name, for messages ("Ratboy_mohawk.tfx")
    std::string format;               // "TressFX 4.0", "TressFX 3.0", "Cem Yuksel .hair"
    std::vector<int> vertexCounts;    // vertices per strand (each >= 2)
    std::vector<Float3> points;       // every strand's vertices, root first, strand after strand
    // Per-vertex attributes (points.size() values each), empty when the file has none.
    std::vector<float> widths;        // .hair thickness
    std::vector<Float3> colors;       // .hair colour
    std::vector<float> opacities;     // .hair 1 - transparency
    // Per-strand thickness scale (TressFX 4.0 offsetStrandThickness), empty when absent.
    std::vector<float> strandThickness;
    // Values the file gives for every vertex when it has no per-vertex array
    // (.hair header defaults).
    std::optional<float> defaultWidth;
    std::optional<Float3> defaultColor;
    std::optional<float> defaultOpacity;
    // Values outside their range that were clamped (a transparency beyond
    // [0, 1], a negative colour), one sentence each, for the converter to
    // print as warnings.
    std::vector<std::string> repairs;

    size_t strandCount() const { return vertexCounts.size(); }
    size_t pointCount() const { return points.size(); }
};

// Reads a .tfx file. Throws std::runtime_error (see above).
HairStrands readTressFx(const std::string& path);
// Parses .tfx bytes already in memory; `name` starts every error message.
HairStrands parseTressFx(const std::vector<std::uint8_t>& bytes, const std::string& name);

// Helpers shared by the readers.
// The whole file; throws std::runtime_error "name: cannot open (reason)".
std::vector<std::uint8_t> readFileBytes(const std::string& path);
// The file name of a path ("a/b/c.tfx" -> "c.tfx"), used in messages.
std::string displayName(const std::string& path);

}  // namespace hdhair::convert
