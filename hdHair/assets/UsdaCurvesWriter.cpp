#include "hdHair/assets/UsdaCurvesWriter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <stdexcept>

#include <fmt/format.h>
#include <glm/glm.hpp>

namespace hdhair::convert {

namespace {

constexpr float kAutoRootWidthPerDiagonal = 0.0015f;
constexpr float kAutoTipPerRoot = 0.2f;
constexpr Float3 kDefaultColor{0.4f, 0.22f, 0.1f};
constexpr double kFocalLength = 50.0, kHorizontalAperture = 20.955, kVerticalAperture = 15.2908;
constexpr double kFrameFill = 0.85;  // the points fill at most this fraction of the frame
constexpr double kPi = 3.14159265358979323846;

glm::dvec3 toVec(const Float3& p) { return {p.x, p.y, p.z}; }

// ---------------------------------------------------------------------------
// Text

void appendNumber(std::string& out, double value) { out += formatNumber(value); }

void appendTuple(std::string& out, const Float3& p) {
    out += '(';
    appendNumber(out, p.x);
    out += ", ";
    appendNumber(out, p.y);
    out += ", ";
    appendNumber(out, p.z);
    out += ')';
}

void appendTuple(std::string& out, const glm::dvec3& p) {
    appendTuple(out, Float3{float(p.x), float(p.y), float(p.z)});
}

template <typename T, typename Append>
void appendArray(std::string& out, const std::vector<T>& values, Append append) {
    out += '[';
    for (size_t i = 0; i < values.size(); ++i) {
        if (i) out += ", ";
        append(out, values[i]);
    }
    out += ']';
}

std::string quoted(const std::string& text) {
    std::string out = "\"";
    for (char c : text) {
        if (c == '"' || c == '\\') out += '\\';
        if (c == '\n' || c == '\r') c = ' ';
        out += c;
    }
    return out + "\"";
}

void appendInterpolation(std::string& out, const char* indent, const char* interpolation) {
    out += fmt::format(" (\n{0}    interpolation = \"{1}\"\n{0})\n", indent, interpolation);
}

// ---------------------------------------------------------------------------
// Rotations

// rotateXYZ angles (degrees) of a rotation matrix (columns: the rotated X, Y, Z
// axes). USD's rotateXYZ rotates about X first: M = Rz(c) * Ry(b) * Rx(a).
glm::dvec3 rotateXYZFromMatrix(const glm::dmat3& m) {
    // glm is column-major: m[col][row]; R[row][col] = m[col][row].
    auto r = [&](int row, int col) { return m[col][row]; };
    double a, b, c;
    const double sb = -r(2, 0);
    if (std::abs(sb) < 0.9999999) {
        b = std::asin(sb);
        a = std::atan2(r(2, 1), r(2, 2));
        c = std::atan2(r(1, 0), r(0, 0));
    } else {
        b = sb > 0 ? kPi / 2 : -kPi / 2;
        c = 0.0;
        a = sb > 0 ? std::atan2(r(0, 1), r(1, 1)) : std::atan2(-r(0, 1), r(1, 1));
    }
    const double toDegrees = 180.0 / kPi;
    return {a * toDegrees, b * toDegrees, c * toDegrees};
}

// The rotation that turns -Z into `forward` with `up` as close to +Y as it can be.
glm::dmat3 lookRotation(const glm::dvec3& forward, const glm::dvec3& up) {
    const glm::dvec3 f = glm::normalize(forward);
    glm::dvec3 right = glm::cross(f, up);
    if (glm::length(right) < 1e-6) {  // looking along the up axis: any horizontal right will do
        right = glm::cross(f, std::abs(f.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 0, 1));
        right = glm::cross(right, f);
    }
    right = glm::normalize(right);
    const glm::dvec3 trueUp = glm::cross(right, f);
    return glm::dmat3(right, trueUp, -f);
}

void appendRotateTranslate(std::string& out, const char* indent, const glm::dmat3& rotation,
                           const std::optional<glm::dvec3>& translate) {
    out += fmt::format("{}float3 xformOp:rotateXYZ = ", indent);
    appendTuple(out, rotateXYZFromMatrix(rotation));
    out += '\n';
    if (translate) {
        out += fmt::format("{}double3 xformOp:translate = ", indent);
        out += fmt::format("({}, {}, {})\n", formatNumber(translate->x), formatNumber(translate->y),
                           formatNumber(translate->z));
        out += fmt::format("{}uniform token[] xformOpOrder = [\"xformOp:translate\", \"xformOp:rotateXYZ\"]\n",
                           indent);
    } else {
        out += fmt::format("{}uniform token[] xformOpOrder = [\"xformOp:rotateXYZ\"]\n", indent);
    }
}

// ---------------------------------------------------------------------------
// Curves

void checkStrands(const HairStrands& s) {
    size_t total = 0;
    for (size_t i = 0; i < s.vertexCounts.size(); ++i) {
        if (s.vertexCounts[i] < 2)
            throw std::invalid_argument(
                fmt::format("{}: strand {} has {} points (at least 2 needed)", s.source, i, s.vertexCounts[i]));
        total += static_cast<size_t>(s.vertexCounts[i]);
    }
    if (s.vertexCounts.empty()) throw std::invalid_argument(s.source + ": no strands");
    auto check = [&](size_t size, const char* what, size_t want) {
        if (size != 0 && size != want)
            throw std::invalid_argument(fmt::format("{}: {} {} for {}", s.source, size, what, want));
    };
    check(s.points.size(), "points", total);
    if (s.points.size() != total)
        throw std::invalid_argument(fmt::format("{}: no points for {} strands", s.source, s.strandCount()));
    check(s.widths.size(), "widths", total);
    check(s.colors.size(), "colors", total);
    check(s.opacities.size(), "opacities", total);
    check(s.strandThickness.size(), "strand thicknesses", s.strandCount());
}

struct Taper {
    float root = 0, tip = 0;
};

void appendCurves(std::string& out, const std::string& name, const HairStrands& s, const UsdaWriteOptions& options,
                  const std::optional<Taper>& taper, WrittenCurves& written) {
    const char* in = "        ";
    // widths: either per point (taper or file), or one constant value.
    std::vector<float> widths;
    const char* widthsInterpolation = "vertex";
    if (taper) {
        widths.reserve(s.points.size());
        for (size_t strand = 0; strand < s.vertexCounts.size(); ++strand) {
            const int n = s.vertexCounts[strand];
            const float scale = s.strandThickness.empty() ? 1.0f : s.strandThickness[strand];
            for (int j = 0; j < n; ++j) {
                const float t = float(j) / float(n - 1);
                widths.push_back(scale * (taper->root + (taper->tip - taper->root) * t));
            }
        }
        written.widths = fmt::format("taper {} -> {}{}", formatNumber(taper->root), formatNumber(taper->tip),
                                     s.strandThickness.empty() ? "" : " x strand thickness");
    } else if (!s.widths.empty()) {
        widths = s.widths;
        written.widths = "per point, from the file";
    } else {
        widths = {*s.defaultWidth};
        widthsInterpolation = "constant";
        written.widths = fmt::format("{}, the file's default", formatNumber(*s.defaultWidth));
    }
    const float maxWidth = widths.empty() ? 0.0f : *std::max_element(widths.begin(), widths.end());

    Bounds bounds;
    for (const Float3& p : s.points) bounds.add(p);
    const float half = 0.5f * maxWidth;

    out += fmt::format("    def BasisCurves \"{}\"\n    {{\n", name);
    out += fmt::format("{}uniform token basis = \"catmullRom\"\n", in);
    out += fmt::format("{}int[] curveVertexCounts = ", in);
    appendArray(out, s.vertexCounts, [](std::string& o, int v) { o += std::to_string(v); });
    out += '\n';
    out += fmt::format("{}float3[] extent = [", in);
    appendTuple(out, Float3{bounds.min.x - half, bounds.min.y - half, bounds.min.z - half});
    out += ", ";
    appendTuple(out, Float3{bounds.max.x + half, bounds.max.y + half, bounds.max.z + half});
    out += "]\n";
    out += fmt::format("{}point3f[] points = ", in);
    appendArray(out, s.points, [](std::string& o, const Float3& p) { appendTuple(o, p); });
    out += '\n';
    out += fmt::format("{}color3f[] primvars:displayColor = ", in);
    if (options.color) {
        out += '[';
        appendTuple(out, *options.color);
        out += ']';
        appendInterpolation(out, in, "constant");
    } else if (!s.colors.empty()) {
        appendArray(out, s.colors, [](std::string& o, const Float3& c) { appendTuple(o, c); });
        appendInterpolation(out, in, "vertex");
    } else {
        out += '[';
        appendTuple(out, s.defaultColor.value_or(kDefaultColor));
        out += ']';
        appendInterpolation(out, in, "constant");
    }
    if (!s.opacities.empty() || s.defaultOpacity) {
        out += fmt::format("{}float[] primvars:displayOpacity = ", in);
        if (!s.opacities.empty()) {
            appendArray(out, s.opacities, [](std::string& o, float v) { appendNumber(o, v); });
            appendInterpolation(out, in, "vertex");
        } else {
            out += '[' + formatNumber(*s.defaultOpacity) + ']';
            appendInterpolation(out, in, "constant");
        }
    }
    out += fmt::format("{}uniform token type = \"cubic\"\n", in);
    out += fmt::format("{}float[] widths = ", in);
    appendArray(out, widths, [](std::string& o, float v) { appendNumber(o, v); });
    appendInterpolation(out, in, widthsInterpolation);
    out += fmt::format("{}uniform token wrap = \"pinned\"\n", in);
    out += "    }\n";
    written.strands = s.strandCount();
    written.points = s.pointCount();
}

struct CameraFraming {
    glm::dvec3 eye;
    glm::dmat3 rotation;
    double nearClip, farClip;
};

// Frames every point of `pointSets` (the strands' and the meshes').
CameraFraming frameCamera(const std::vector<const std::vector<Float3>*>& pointSets, const glm::dvec3& from,
                          const glm::dvec3& up) {
    Bounds bounds;
    for (const std::vector<Float3>* points : pointSets)
        for (const Float3& p : *points) bounds.add(p);
    const glm::dvec3 target = 0.5 * (toVec(bounds.min) + toVec(bounds.max));
    CameraFraming c;
    c.rotation = lookRotation(-from, up);
    const glm::dvec3 right = c.rotation[0], camUp = c.rotation[1], forward = -c.rotation[2];
    const double kx = kFocalLength / (kHorizontalAperture / 2), ky = kFocalLength / (kVerticalAperture / 2);
    double dist = 0.0, minDepth = 0.0, maxDepth = 0.0;
    for (const std::vector<Float3>* points : pointSets) {
        for (const Float3& p : *points) {
            const glm::dvec3 rel = toVec(p) - target;
            const double a = glm::dot(rel, right), b = glm::dot(rel, camUp), e = glm::dot(rel, forward);
            dist = std::max({dist, std::abs(a) * kx / kFrameFill - e, std::abs(b) * ky / kFrameFill - e});
            minDepth = std::min(minDepth, e);
            maxDepth = std::max(maxDepth, e);
        }
    }
    const double diagonal = std::max(double(bounds.diagonal()), 1e-3);
    // In front of the nearest point, whatever the asset's shape.
    dist = std::max({dist, -minDepth + 0.05 * diagonal, 1e-3});
    c.eye = target - forward * dist;
    c.nearClip = std::max(0.5 * (dist + minDepth), 1e-4 * dist);
    c.farClip = 2.0 * (dist + maxDepth);
    return c;
}

void checkMesh(const MeshInput& input) {
    const PolygonMesh& m = input.mesh;
    static const std::set<std::string> schemes = {"catmullClark", "loop", "bilinear", "none"};
    if (!schemes.count(input.subdivisionScheme))
        throw std::invalid_argument(fmt::format("{}: unknown subdivision scheme '{}' (catmullClark, loop, bilinear "
                                                "or none)",
                                                m.source, input.subdivisionScheme));
    size_t corners = 0;
    for (size_t f = 0; f < m.faceVertexCounts.size(); ++f) {
        if (m.faceVertexCounts[f] < 3)
            throw std::invalid_argument(fmt::format("{}: face {} has {} vertices", m.source, f, m.faceVertexCounts[f]));
        corners += size_t(m.faceVertexCounts[f]);
    }
    if (corners != m.faceVertexIndices.size())
        throw std::invalid_argument(fmt::format("{}: the faces need {} vertex indices, found {}", m.source, corners,
                                                m.faceVertexIndices.size()));
    for (int index : m.faceVertexIndices)
        if (index < 0 || size_t(index) >= m.points.size())
            throw std::invalid_argument(fmt::format("{}: vertex index {} is outside the {} points", m.source, index,
                                                    m.points.size()));
}

void appendMesh(std::string& out, const std::string& name, const MeshInput& input, WrittenMesh& written) {
    const PolygonMesh& m = input.mesh;
    const char* in = "        ";
    Bounds bounds;
    for (const Float3& p : m.points) bounds.add(p);
    out += fmt::format("    def Mesh \"{}\"\n    {{\n", name);
    out += fmt::format("{}float3[] extent = [", in);
    appendTuple(out, bounds.min);
    out += ", ";
    appendTuple(out, bounds.max);
    out += "]\n";
    out += fmt::format("{}int[] faceVertexCounts = ", in);
    appendArray(out, m.faceVertexCounts, [](std::string& o, int v) { o += std::to_string(v); });
    out += fmt::format("\n{}int[] faceVertexIndices = ", in);
    appendArray(out, m.faceVertexIndices, [](std::string& o, int v) { o += std::to_string(v); });
    out += fmt::format("\n{}point3f[] points = ", in);
    appendArray(out, m.points, [](std::string& o, const Float3& p) { appendTuple(o, p); });
    out += fmt::format("\n{}color3f[] primvars:displayColor = [", in);
    appendTuple(out, input.color);
    out += "]";
    appendInterpolation(out, in, "constant");
    out += fmt::format("{}uniform token subdivisionScheme = \"{}\"\n", in, input.subdivisionScheme);
    out += "    }\n";
    written.points = m.points.size();
    written.faces = m.faceVertexCounts.size();
}

void appendCamera(std::string& out, const CameraFraming& c) {
    const char* in = "        ";
    out += "    def Camera \"main_cam\"\n    {\n";
    out += fmt::format("{}float2 clippingRange = ({}, {})\n", in, formatNumber(c.nearClip), formatNumber(c.farClip));
    out += fmt::format("{}float focalLength = {}\n", in, formatNumber(kFocalLength));
    out += fmt::format("{}float horizontalAperture = {}\n", in, formatNumber(kHorizontalAperture));
    out += fmt::format("{}token projection = \"perspective\"\n", in);
    out += fmt::format("{}float verticalAperture = {}\n", in, formatNumber(kVerticalAperture));
    appendRotateTranslate(out, in, c.rotation, c.eye);
    out += "    }\n";
}

void appendLight(std::string& out, const CameraFraming& c, const glm::dvec3& up) {
    const char* in = "        ";
    const glm::dvec3 right = c.rotation[0], toCamera = c.rotation[2];
    // Where the light comes from: above, in front, a little to the right.
    const glm::dvec3 from = glm::normalize(0.4 * right + 0.8 * up + 0.7 * toCamera);
    out += "    def DistantLight \"key_light\"\n    {\n";
    out += fmt::format("{}float inputs:angle = 1\n", in);
    out += fmt::format("{}color3f inputs:color = (1, 1, 1)\n", in);
    out += fmt::format("{}float inputs:intensity = 2\n", in);
    appendRotateTranslate(out, in, lookRotation(-from, up), std::nullopt);
    out += "    }\n";
}

// splitmix64: a tiny, well-mixed hash for deterministic follow-strand offsets.
uint64_t mix(uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

double unitRandom(uint64_t key) { return double(mix(key) >> 11) * (1.0 / 9007199254740992.0); }

glm::dvec3 anyPerpendicular(const glm::dvec3& t) {
    const glm::dvec3 axis = std::abs(t.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    return glm::normalize(glm::cross(t, axis));
}

// Rotates v by the rotation that takes unit vector a to unit vector b.
glm::dvec3 transport(const glm::dvec3& v, const glm::dvec3& a, const glm::dvec3& b) {
    const glm::dvec3 axis = glm::cross(a, b);
    const double s = glm::length(axis), c = glm::dot(a, b);
    if (s < 1e-12) return c > 0 ? v : -v;
    const glm::dvec3 k = axis / s;
    return v * c + glm::cross(k, v) * s + k * glm::dot(k, v) * (1 - c);
}

// Throws std::invalid_argument for the first option that cannot be written.
void checkWriteOptions(const UsdaWriteOptions& options) {
    if (options.upAxis != 'Y' && options.upAxis != 'Z')
        throw std::invalid_argument(fmt::format("the up axis must be Y or Z, not '{}'", options.upAxis));
    if (options.rootWidth && !(std::isfinite(*options.rootWidth) && *options.rootWidth > 0))
        throw std::invalid_argument("the root width must be a positive number");
    if (options.tipWidth && !(std::isfinite(*options.tipWidth) && *options.tipWidth >= 0))
        throw std::invalid_argument("the tip width must be a number >= 0");
    if (!(std::isfinite(options.metersPerUnit) && options.metersPerUnit > 0))
        throw std::invalid_argument("metersPerUnit must be a positive number");
}

// The direction from the bounds' centre to the camera: --cameraFrom's, else in front.
glm::dvec3 cameraDirection(const UsdaWriteOptions& options) {
    glm::dvec3 from = options.upAxis == 'Y' ? glm::dvec3(0, 0, 1) : glm::dvec3(0, -1, 0);
    if (options.cameraFrom) {
        from = toVec(*options.cameraFrom);
        if (!(glm::length(from) > 1e-9) || !std::isfinite(glm::length(from)))
            throw std::invalid_argument("the camera direction must be a non-zero vector");
    }
    return from;
}

// The taper of strands without widths of their own (and of every strand when a width option is given).
Taper automaticTaper(const UsdaWriteOptions& options, const Bounds& bounds) {
    Taper autoTaper;
    autoTaper.root = options.rootWidth.value_or(kAutoRootWidthPerDiagonal * bounds.diagonal());
    if (!(autoTaper.root > 0)) autoTaper.root = 1e-3f;  // every point in one place
    autoTaper.tip = options.tipWidth.value_or(kAutoTipPerRoot * autoTaper.root);
    return autoTaper;
}

// The prims' names under /World, each unique.
struct PrimNames {
    std::vector<std::string> curves, meshes;
};

// Unique prim names for the curves, then the meshes, made from their input names.
PrimNames uniquePrimNames(const std::vector<CurvesInput>& inputs, const std::vector<MeshInput>& meshes,
                          const UsdaWriteOptions& options) {
    std::set<std::string> used;
    if (options.camera) used = {"main_cam", "key_light"};
    auto uniqueName = [&](const std::string& wanted) {
        const std::string base = usdIdentifier(wanted);
        std::string name = base;
        for (int k = 2; used.count(name); ++k) name = fmt::format("{}_{}", base, k);
        used.insert(name);
        return name;
    };
    PrimNames names;
    for (const CurvesInput& input : inputs) names.curves.push_back(uniqueName(input.name));
    for (const MeshInput& mesh : meshes) names.meshes.push_back(uniqueName(mesh.name));
    return names;
}

// The layer's metadata and the opening of its World prim.
void appendLayerHeader(std::string& out, const UsdaWriteOptions& options) {
    out += "#usda 1.0\n(\n";
    if (!options.doc.empty()) out += "    doc = " + quoted(options.doc) + "\n";
    out += "    defaultPrim = \"World\"\n";
    out += "    metersPerUnit = " + formatNumber(options.metersPerUnit) + "\n";
    out += fmt::format("    upAxis = \"{}\"\n", options.upAxis);
    out += ")\n\n";
    out += "def Xform \"World\" (\n    kind = \"component\"\n)\n{\n";
}

// The camera framing every curve and mesh point, looking along -from.
CameraFraming frameInputs(const std::vector<CurvesInput>& inputs, const std::vector<MeshInput>& meshes,
                          const glm::dvec3& from, const glm::dvec3& up) {
    std::vector<const std::vector<Float3>*> pointSets;
    for (const CurvesInput& input : inputs) pointSets.push_back(&input.strands.points);
    for (const MeshInput& mesh : meshes) pointSets.push_back(&mesh.mesh.points);
    return frameCamera(pointSets, from, up);
}

}  // namespace

void Bounds::add(const Float3& p) {
    min = {std::min(min.x, p.x), std::min(min.y, p.y), std::min(min.z, p.z)};
    max = {std::max(max.x, p.x), std::max(max.y, p.y), std::max(max.z, p.z)};
}

float Bounds::diagonal() const {
    if (empty()) return 0.0f;
    return float(glm::length(toVec(max) - toVec(min)));
}

std::string formatNumber(double value) {
    if (!std::isfinite(value)) throw std::invalid_argument(fmt::format("cannot write the number {}", value));
    if (std::abs(value) < 1e-6) return "0";
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.6g", value);
    std::string s = buffer;
    const size_t e = s.find('e');
    if (e != std::string::npos) {
        // Rewrite "1.5e+07" / "1.5e-05" without the exponent, keeping the 6 digits.
        const double rounded = std::strtod(buffer, nullptr);
        const int exponent = std::atoi(s.c_str() + e + 1);
        const int decimals = exponent < 0 ? 5 - exponent : 0;
        std::snprintf(buffer, sizeof buffer, "%.*f", decimals, rounded);
        s = buffer;
    }
    if (s.find('.') != std::string::npos) {
        while (s.back() == '0') s.pop_back();
        if (s.back() == '.') s.pop_back();
    }
    if (s == "-0") s = "0";
    return s;
}

std::string usdIdentifier(const std::string& text) {
    std::string out;
    for (char c : text) {
        const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
        out += ok ? c : '_';
    }
    if (out.empty()) return "hair";
    if (out[0] >= '0' && out[0] <= '9') out.insert(out.begin(), '_');
    return out;
}

CurvesUsda buildCurvesUsda(const std::vector<CurvesInput>& inputs, const UsdaWriteOptions& options,
                           const std::vector<MeshInput>& meshes) {
    if (inputs.empty() && meshes.empty()) throw std::invalid_argument("no hair to write");
    checkWriteOptions(options);
    const glm::dvec3 up = options.upAxis == 'Y' ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1);
    const glm::dvec3 from = cameraDirection(options);

    CurvesUsda result;
    for (const CurvesInput& input : inputs) {
        checkStrands(input.strands);
        for (const Float3& p : input.strands.points) result.bounds.add(p);
    }
    for (const MeshInput& mesh : meshes) checkMesh(mesh);
    const Taper autoTaper = automaticTaper(options, result.bounds);
    const bool widthOption = options.rootWidth || options.tipWidth;
    result.rootWidth = autoTaper.root;
    result.tipWidth = autoTaper.tip;
    const PrimNames names = uniquePrimNames(inputs, meshes, options);

    size_t totalPoints = 0;
    for (const CurvesInput& input : inputs) totalPoints += input.strands.pointCount();
    std::string& out = result.text;
    out.reserve(totalPoints * 40 + 4096);
    appendLayerHeader(out, options);

    std::optional<CameraFraming> framing;
    if (options.camera) {
        framing = frameInputs(inputs, meshes, from, up);
        appendCamera(out, *framing);
    }
    for (size_t i = 0; i < inputs.size(); ++i) {
        const HairStrands& s = inputs[i].strands;
        std::optional<Taper> taper;
        if (widthOption || (s.widths.empty() && !s.defaultWidth)) taper = autoTaper;
        if (framing || i > 0) out += '\n';
        WrittenCurves written;
        written.path = "/World/" + names.curves[i];
        appendCurves(out, names.curves[i], s, options, taper, written);
        result.curves.push_back(written);
    }
    for (size_t i = 0; i < meshes.size(); ++i) {
        if (framing || i > 0 || !inputs.empty()) out += '\n';
        WrittenMesh written;
        written.path = "/World/" + names.meshes[i];
        appendMesh(out, names.meshes[i], meshes[i], written);
        result.meshes.push_back(written);
    }
    if (framing) {
        out += '\n';
        appendLight(out, *framing, up);
    }
    out += "}\n\n";
    return result;
}

void writeFileAtomically(const std::string& path, const std::string& text) {
    namespace fs = std::filesystem;
    const fs::path target = fs::absolute(path);
    const fs::path temporary = target.parent_path() / ("." + target.filename().string() + ".tmp");
    {
        std::ofstream out(temporary, std::ios::binary);
        if (!out)
            throw std::runtime_error(fmt::format("cannot write '{}' (cannot create {})", path, temporary.string()));
        out.write(text.data(), static_cast<std::streamsize>(text.size()));
        out.close();
        if (!out) {
            std::error_code ignored;
            fs::remove(temporary, ignored);
            throw std::runtime_error(fmt::format("cannot write '{}' (disk full?)", path));
        }
    }
    std::error_code error;
    fs::rename(temporary, target, error);
    if (error) {
        std::error_code ignored;
        fs::remove(temporary, ignored);
        throw std::runtime_error(fmt::format("cannot write '{}' ({})", path, error.message()));
    }
}

namespace {

// The asset's header values (defaults, name) with no strands: what the
// subsampling and follow-strand passes fill anew.
HairStrands withoutStrands(const HairStrands& strands) {
    HairStrands out = strands;
    out.vertexCounts.clear();
    out.points.clear();
    out.widths.clear();
    out.colors.clear();
    out.opacities.clear();
    out.strandThickness.clear();
    return out;
}

}  // namespace

HairStrands subsampleStrands(const HairStrands& strands, size_t maxStrands) {
    const size_t n = strands.strandCount();
    if (maxStrands >= n || maxStrands == 0) return strands;
    std::vector<size_t> firstPoint(n + 1, 0);
    for (size_t s = 0; s < n; ++s) firstPoint[s + 1] = firstPoint[s] + static_cast<size_t>(strands.vertexCounts[s]);
    HairStrands out = withoutStrands(strands);
    for (size_t i = 0; i < maxStrands; ++i) {
        const size_t s = i * n / maxStrands;
        out.vertexCounts.push_back(strands.vertexCounts[s]);
        const size_t a = firstPoint[s], b = firstPoint[s + 1];
        out.points.insert(out.points.end(), strands.points.begin() + long(a), strands.points.begin() + long(b));
        if (!strands.widths.empty())
            out.widths.insert(out.widths.end(), strands.widths.begin() + long(a), strands.widths.begin() + long(b));
        if (!strands.colors.empty())
            out.colors.insert(out.colors.end(), strands.colors.begin() + long(a), strands.colors.begin() + long(b));
        if (!strands.opacities.empty())
            out.opacities.insert(out.opacities.end(), strands.opacities.begin() + long(a),
                                 strands.opacities.begin() + long(b));
        if (!strands.strandThickness.empty()) out.strandThickness.push_back(strands.strandThickness[s]);
    }
    return out;
}

HairStrands addFollowStrands(const HairStrands& strands, const FollowOptions& options) {
    if (options.perGuide < 0) throw std::invalid_argument("the follow strand count must be >= 0");
    if (!(std::isfinite(options.radius) && options.radius >= 0))
        throw std::invalid_argument("the follow radius must be a number >= 0");
    if (!(std::isfinite(options.tipSeparation) && options.tipSeparation >= 0))
        throw std::invalid_argument("the follow tip separation must be a number >= 0");
    if (options.perGuide == 0) return strands;
    const size_t copies = static_cast<size_t>(options.perGuide) + 1;
    HairStrands out = withoutStrands(strands);
    out.vertexCounts.reserve(strands.strandCount() * copies);
    out.points.reserve(strands.pointCount() * copies);
    size_t first = 0;
    for (size_t s = 0; s < strands.strandCount(); ++s) {
        const size_t n = static_cast<size_t>(strands.vertexCounts[s]);
        const Float3* p = strands.points.data() + first;
        for (size_t copy = 0; copy < copies; ++copy) {
            out.vertexCounts.push_back(static_cast<int>(n));
            if (copy == 0) {
                out.points.insert(out.points.end(), p, p + n);
            } else {
                // A random point in the disc of `radius` around the root, perpendicular to the root tangent.
                const uint64_t key = (uint64_t(s) << 20) ^ uint64_t(copy);
                const double r = options.radius * std::sqrt(unitRandom(key * 2 + 1));
                const double angle = 2 * kPi * unitRandom(key * 2 + 2);
                glm::dvec3 tangent = toVec(p[1]) - toVec(p[0]);
                tangent = glm::length(tangent) > 0 ? glm::normalize(tangent) : glm::dvec3(0, 1, 0);
                const glm::dvec3 u = anyPerpendicular(tangent), v = glm::cross(tangent, u);
                glm::dvec3 offset = r * (std::cos(angle) * u + std::sin(angle) * v);
                for (size_t j = 0; j < n; ++j) {
                    if (j > 0) {
                        // Carry the offset along with the strand's turning tangent.
                        const glm::dvec3 d = toVec(p[std::min(j + 1, n - 1)]) - toVec(p[j - 1]);
                        if (glm::length(d) > 0) {
                            const glm::dvec3 next = glm::normalize(d);
                            offset = transport(offset, tangent, next);
                            tangent = next;
                        }
                    }
                    const double grow = 1.0 + options.tipSeparation * double(j) / double(n - 1);
                    const glm::dvec3 q = toVec(p[j]) + offset * grow;
                    out.points.push_back({float(q.x), float(q.y), float(q.z)});
                }
            }
            if (!strands.widths.empty())
                out.widths.insert(out.widths.end(), strands.widths.begin() + long(first),
                                  strands.widths.begin() + long(first + n));
            if (!strands.colors.empty())
                out.colors.insert(out.colors.end(), strands.colors.begin() + long(first),
                                  strands.colors.begin() + long(first + n));
            if (!strands.opacities.empty())
                out.opacities.insert(out.opacities.end(), strands.opacities.begin() + long(first),
                                     strands.opacities.begin() + long(first + n));
            if (!strands.strandThickness.empty()) out.strandThickness.push_back(strands.strandThickness[s]);
        }
        first += n;
    }
    return out;
}

}  // namespace hdhair::convert
