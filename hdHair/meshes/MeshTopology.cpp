#include "hdHair/meshes/MeshTopology.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/scene/MeshPrim.h"

namespace hdhair {

namespace {

const char* plural(size_t count, const char* singular, const char* many) { return count == 1 ? singular : many; }

bool isFinite(const glm::vec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

// How many elements had one problem, and the first of them: one warning
// per problem, however large the mesh.
struct Tally {
    size_t count = 0;
    size_t first = 0;
    void add(size_t element) {
        if (count++ == 0) first = element;
    }
};

// Parses a token with `names[i]` meaning value i; unknown tokens warn and
// keep `fallback`.
template <typename Enum, size_t N>
Enum parseToken(const std::string& token, const char* const (&names)[N], Enum fallback, const std::string& where,
                Diagnostics& diagnostics) {
    for (size_t i = 0; i < N; ++i)
        if (token == names[i]) return static_cast<Enum>(i);
    diagnostics.warn(where, fmt::format("unknown value '{}' (expected {}); using {}", token, fmt::join(names, ", "),
                                        names[static_cast<size_t>(fallback)]));
    return fallback;
}

const char* const kSchemes[] = {"catmullClark", "loop", "bilinear", "none"};
const char* const kBoundaries[] = {"none", "edgeOnly", "edgeAndCorner"};
const char* const kFaceVarying[] = {"none", "cornersOnly", "cornersPlus1", "cornersPlus2", "boundaries", "all"};
const char* const kTriangleRules[] = {"catmullClark", "smooth"};
const char* const kOrientations[] = {"rightHanded", "leftHanded"};

// Newell's normal of a polygon: twice its area along its normal; zero for a
// polygon of no area.
glm::dvec3 newellNormal(const std::vector<glm::vec3>& points, const int* indices, int count) {
    glm::dvec3 normal(0.0);
    for (int i = 0; i < count; ++i) {
        const glm::dvec3 a(points[size_t(indices[i])]);
        const glm::dvec3 b(points[size_t(indices[(i + 1) % count])]);
        normal += glm::dvec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
    }
    return normal;
}

bool isPoint(int vertex, const MeshTopology& topology) {
    return vertex >= 0 && size_t(vertex) < topology.points.size();
}

// A sharpness as OpenSubdiv takes it: negative or non-finite ones are 0
// (smooth), counted in `bad` as `element`.
float checkedSharpness(float sharpness, size_t element, Tally& bad) {
    if (std::isfinite(sharpness) && sharpness >= 0.0f) return sharpness;
    bad.add(element);
    return 0.0f;
}

// The warnings for tags (`kind`: "crease edge", "corner") naming a vertex
// outside the points, and for sharpnesses repaired to 0.
void reportTags(Diagnostics& diagnostics, const MeshPrim& prim, const char* indicesAttribute,
                const char* sharpnessAttribute, const std::string& kind, const Tally& outOfRange,
                const Tally& badSharpness, size_t points) {
    if (outOfRange.count > 0)
        diagnostics.warn(prim.path + "." + indicesAttribute,
                         fmt::format("{} {} a vertex outside the {} points (first: {} {}); {}", outOfRange.count,
                                     plural(outOfRange.count, (kind + " names").c_str(), (kind + "s name").c_str()),
                                     points, kind, outOfRange.first,
                                     plural(outOfRange.count, "it is ignored", "they are ignored")));
    if (badSharpness.count > 0)
        diagnostics.warn(prim.path + "." + sharpnessAttribute,
                         fmt::format("{} {} {} negative or not finite (first: {} {}); using 0 (smooth)",
                                     badSharpness.count, kind,
                                     plural(badSharpness.count, "sharpness is", "sharpnesses are"), kind,
                                     badSharpness.first));
}

// The vertices of each crease edge and its sharpness, from USD's chains.
void readCreases(const MeshPrim& prim, MeshTopology& topology, Diagnostics& diagnostics) {
    if (prim.creaseIndices.empty() && prim.creaseLengths.empty() && prim.creaseSharpnesses.empty()) return;
    uint64_t chained = 0, edges = 0;
    for (int length : prim.creaseLengths) {
        if (length < 2) {
            diagnostics.warn(prim.path + ".creaseLengths",
                             fmt::format("a crease of {} vertices has no edge; creases ignored", length));
            return;
        }
        chained += uint64_t(length);
        edges += uint64_t(length) - 1;
    }
    if (chained != prim.creaseIndices.size()) {
        diagnostics.warn(prim.path + ".creaseIndices",
                         fmt::format("creaseLengths add up to {} vertices, found {}; creases ignored", chained,
                                     prim.creaseIndices.size()));
        return;
    }
    const bool perCrease = prim.creaseSharpnesses.size() == prim.creaseLengths.size();
    if (!perCrease && prim.creaseSharpnesses.size() != edges) {
        diagnostics.warn(prim.path + ".creaseSharpnesses",
                         fmt::format("needs one sharpness per crease ({}) or per crease edge ({}), found {}; creases "
                                     "ignored",
                                     prim.creaseLengths.size(), edges, prim.creaseSharpnesses.size()));
        return;
    }
    Tally outOfRange, badSharpness;
    size_t vertex = 0, edge = 0;
    for (size_t crease = 0; crease < prim.creaseLengths.size(); ++crease) {
        for (int k = 0; k + 1 < prim.creaseLengths[crease]; ++k, ++edge) {
            const int a = prim.creaseIndices[vertex + size_t(k)], b = prim.creaseIndices[vertex + size_t(k) + 1];
            if (!isPoint(a, topology) || !isPoint(b, topology)) {
                outOfRange.add(edge);
                continue;
            }
            topology.creaseEdges.push_back(a);
            topology.creaseEdges.push_back(b);
            topology.creaseSharpnesses.push_back(
                checkedSharpness(prim.creaseSharpnesses[perCrease ? crease : edge], edge, badSharpness));
        }
        vertex += size_t(prim.creaseLengths[crease]);
    }
    reportTags(diagnostics, prim, "creaseIndices", "creaseSharpnesses", "crease edge", outOfRange, badSharpness,
               topology.points.size());
}

void readCorners(const MeshPrim& prim, MeshTopology& topology, Diagnostics& diagnostics) {
    if (prim.cornerIndices.empty() && prim.cornerSharpnesses.empty()) return;
    if (prim.cornerIndices.size() != prim.cornerSharpnesses.size()) {
        diagnostics.warn(prim.path + ".cornerSharpnesses",
                         fmt::format("needs one sharpness per corner ({}), found {}; corners ignored",
                                     prim.cornerIndices.size(), prim.cornerSharpnesses.size()));
        return;
    }
    Tally outOfRange, badSharpness;
    for (size_t i = 0; i < prim.cornerIndices.size(); ++i) {
        if (!isPoint(prim.cornerIndices[i], topology)) {
            outOfRange.add(i);
            continue;
        }
        topology.corners.push_back(prim.cornerIndices[i]);
        topology.cornerSharpnesses.push_back(checkedSharpness(prim.cornerSharpnesses[i], i, badSharpness));
    }
    reportTags(diagnostics, prim, "cornerIndices", "cornerSharpnesses", "corner", outOfRange, badSharpness,
               topology.points.size());
}

// Non-finite points become the mean of the finite points they share a face
// with (the origin when there are none), so that subdivision stencils
// around them stay finite; the faces using them are holes.
std::vector<bool> repairPoints(const MeshPrim& prim, MeshTopology& topology, Diagnostics& diagnostics) {
    std::vector<bool> bad(topology.points.size(), false);
    Tally nonFinite;
    for (size_t p = 0; p < topology.points.size(); ++p) {
        if (isFinite(topology.points[p])) continue;
        bad[p] = true;
        nonFinite.add(p);
    }
    if (nonFinite.count == 0) return bad;
    std::vector<glm::dvec3> sums(topology.points.size(), glm::dvec3(0.0));
    std::vector<uint32_t> counts(topology.points.size(), 0);
    size_t corner = 0;
    for (size_t f = 0; f < topology.faceCount(); ++f) {
        const int n = topology.faceVertexCounts[f];
        for (int i = 0; i < n; ++i) {
            const size_t v = size_t(topology.faceVertexIndices[corner + size_t(i)]);
            if (!bad[v]) continue;
            for (int j = 0; j < n; ++j) {
                const size_t w = size_t(topology.faceVertexIndices[corner + size_t(j)]);
                if (bad[w]) continue;
                sums[v] += glm::dvec3(topology.points[w]);
                ++counts[v];
            }
        }
        corner += size_t(n);
    }
    for (size_t p = 0; p < topology.points.size(); ++p)
        if (bad[p]) topology.points[p] = counts[p] > 0 ? glm::vec3(sums[p] / double(counts[p])) : glm::vec3(0.0f);
    diagnostics.warn(prim.path + ".points",
                     fmt::format("{} {} not finite (first: points[{}]); the faces using {} are not drawn",
                                 nonFinite.count, plural(nonFinite.count, "point is", "points are"), nonFinite.first,
                                 plural(nonFinite.count, "it", "them")));
    return bad;
}

// The subdivision options, each an authored token; returns whether the faces
// wind leftHanded.
bool readSubdivisionOptions(const MeshPrim& prim, MeshTopology& topology, Diagnostics& diagnostics) {
    auto at = [&](const char* attribute) { return prim.path + "." + attribute; };
    topology.scheme = parseToken(prim.subdivisionScheme, kSchemes, SubdivisionScheme::CatmullClark,
                                 at("subdivisionScheme"), diagnostics);
    topology.boundary = parseToken(prim.interpolateBoundary, kBoundaries, BoundaryInterpolation::EdgeAndCorner,
                                   at("interpolateBoundary"), diagnostics);
    topology.faceVarying = parseToken(prim.faceVaryingLinearInterpolation, kFaceVarying,
                                      FaceVaryingInterpolation::CornersPlus1, at("faceVaryingLinearInterpolation"),
                                      diagnostics);
    topology.triangles = parseToken(prim.triangleSubdivisionRule, kTriangleRules, TriangleSubdivision::CatmullClark,
                                    at("triangleSubdivisionRule"), diagnostics);
    return parseToken(prim.orientation, kOrientations, 0, at("orientation"), diagnostics) == 1;
}

// What readFaces left out, for one warning per problem.
struct FaceProblems {
    Tally tooFew, outOfRange, negative;
    size_t missing = 0, firstMissing = 0;
    uint64_t corner = 0;  // the faceVertexIndices the authored counts use
};

// Faces: each takes its count of indices in order. Faces with fewer than
// 3 vertices, past the end of the indices, or naming a point that does
// not exist are left out; the others keep their authored numbers.
FaceProblems readFaces(const MeshPrim& prim, bool leftHanded, MeshTopology& topology) {
    FaceProblems problems;
    uint64_t& corner = problems.corner;
    const uint64_t indexCount = prim.faceVertexIndices.size();
    for (size_t face = 0; face < prim.faceVertexCounts.size(); ++face) {
        const int n = prim.faceVertexCounts[face];
        if (n < 0) {
            problems.negative.add(face);
            continue;
        }
        const uint64_t begin = corner;
        corner += uint64_t(n);
        if (corner > indexCount) {
            if (problems.missing++ == 0) problems.firstMissing = face;
            continue;
        }
        if (n < 3) {
            problems.tooFew.add(face);
            continue;
        }
        const int* indices = prim.faceVertexIndices.data() + begin;
        if (std::any_of(indices, indices + n,
                        [&](int v) { return v < 0 || size_t(v) >= prim.points.size(); })) {
            problems.outOfRange.add(face);
            continue;
        }
        topology.faceVertexCounts.push_back(n);
        topology.authoredFace.push_back(int(face));
        for (int i = 0; i < n; ++i) {
            // leftHanded faces wind clockwise seen from their front: reversed
            // (the first corner kept), every face is counter-clockwise.
            const int k = leftHanded ? (n - i) % n : i;
            topology.faceVertexIndices.push_back(indices[k]);
            topology.authoredCorner.push_back(int(begin) + k);
        }
    }
    return problems;
}

void reportFaceProblems(const MeshPrim& prim, const FaceProblems& problems, Diagnostics& diagnostics) {
    const std::string faces = prim.path + ".faceVertexCounts";
    const std::string indices = prim.path + ".faceVertexIndices";
    const uint64_t indexCount = prim.faceVertexIndices.size();
    const Tally& negative = problems.negative;
    const Tally& tooFew = problems.tooFew;
    const Tally& outOfRange = problems.outOfRange;
    const size_t missing = problems.missing;
    if (negative.count > 0)
        diagnostics.warn(faces, fmt::format("{} {} a negative vertex count (first: face {}); not drawn", negative.count,
                                            plural(negative.count, "face has", "faces have"), negative.first));
    if (tooFew.count > 0)
        diagnostics.warn(faces, fmt::format("{} {} fewer than 3 vertices (first: face {}); not drawn", tooFew.count,
                                            plural(tooFew.count, "face has", "faces have"), tooFew.first));
    if (missing > 0)
        diagnostics.warn(faces, fmt::format("the faces need {} faceVertexIndices, found {}; the last {} {} (from face "
                                            "{}) not drawn",
                                            problems.corner, indexCount, missing,
                                            plural(missing, "face is", "faces are"), problems.firstMissing));
    else if (problems.corner < indexCount)
        diagnostics.warn(indices, fmt::format("{} indices, {} more than the faces use; the rest are ignored",
                                              indexCount, indexCount - problems.corner));
    if (outOfRange.count > 0)
        diagnostics.warn(indices,
                         fmt::format("{} {} a point outside the {} points (first: face {}); not drawn", outOfRange.count,
                                     plural(outOfRange.count, "face names", "faces name"), prim.points.size(),
                                     outOfRange.first));
}

// Holes: authored face numbers, mapped to the kept faces.
void readHoles(const MeshPrim& prim, MeshTopology& topology, Diagnostics& diagnostics) {
    topology.hole.assign(topology.faceCount(), false);
    std::vector<int> keptIndex(prim.faceVertexCounts.size(), -1);
    for (size_t f = 0; f < topology.faceCount(); ++f) keptIndex[size_t(topology.authoredFace[f])] = int(f);
    Tally badHole;
    for (size_t i = 0; i < prim.holeIndices.size(); ++i) {
        const int face = prim.holeIndices[i];
        if (face < 0 || size_t(face) >= keptIndex.size()) {
            badHole.add(i);
            continue;
        }
        if (keptIndex[size_t(face)] >= 0) topology.hole[size_t(keptIndex[size_t(face)])] = true;
    }
    if (badHole.count > 0)
        diagnostics.warn(prim.path + ".holeIndices",
                         fmt::format("{} {} outside the {} faces (first: holeIndices[{}]); ignored", badHole.count,
                                     plural(badHole.count, "hole is", "holes are"), keptIndex.size(), badHole.first));
}

// Faces using a repaired point become holes; faces of no area are warned
// about.
void checkFaceAreas(const MeshPrim& prim, const std::vector<bool>& badPoint, MeshTopology& topology,
                    Diagnostics& diagnostics) {
    size_t first = 0;
    Tally zeroArea;
    double extent = 0.0;
    for (const glm::vec3& p : topology.points) extent = std::max(extent, double(glm::length(p)));
    for (size_t f = 0; f < topology.faceCount(); ++f) {
        const int n = topology.faceVertexCounts[f];
        const int* indices = topology.faceVertexIndices.data() + first;
        first += size_t(n);
        if (std::any_of(indices, indices + n, [&](int v) { return badPoint[size_t(v)]; })) {
            topology.hole[f] = true;
            continue;
        }
        // Zero area (collinear or repeated points): drawn, though no pixel
        // is ever covered; its normal is none, so it lends none to its
        // vertices (MeshPreparation).
        if (glm::length(newellNormal(topology.points, indices, n)) <= 1e-12 * std::max(extent * extent, 1e-30))
            zeroArea.add(size_t(topology.authoredFace[f]));
    }
    if (zeroArea.count > 0)
        diagnostics.warn(prim.path + ".faceVertexCounts",
                         fmt::format("{} {} no area (first: face {}); {} no pixels and no normal", zeroArea.count,
                                     plural(zeroArea.count, "face has", "faces have"), zeroArea.first,
                                     plural(zeroArea.count, "it covers", "they cover")));
}

void checkLoopTriangles(const MeshPrim& prim, MeshTopology& topology, Diagnostics& diagnostics) {
    if (topology.scheme == SubdivisionScheme::Loop &&
        std::any_of(topology.faceVertexCounts.begin(), topology.faceVertexCounts.end(), [](int n) { return n != 3; })) {
        diagnostics.warn(prim.path + ".subdivisionScheme",
                         "loop subdivision needs triangles only; drawn as polygons (none)");
        topology.scheme = SubdivisionScheme::None;
    }
}

}  // namespace

const char* toString(SubdivisionScheme scheme) { return kSchemes[static_cast<size_t>(scheme)]; }

MeshTopology checkMeshTopology(const MeshPrim& prim, Diagnostics& diagnostics) {
    MeshTopology topology;
    const bool leftHanded = readSubdivisionOptions(prim, topology, diagnostics);

    topology.points = prim.points;
    topology.authoredFaceCount = prim.faceVertexCounts.size();
    topology.authoredPointCount = prim.points.size();
    topology.authoredCornerCount = prim.faceVertexIndices.size();

    reportFaceProblems(prim, readFaces(prim, leftHanded, topology), diagnostics);
    readHoles(prim, topology, diagnostics);
    const std::vector<bool> badPoint = repairPoints(prim, topology, diagnostics);
    checkFaceAreas(prim, badPoint, topology, diagnostics);
    checkLoopTriangles(prim, topology, diagnostics);
    readCreases(prim, topology, diagnostics);
    readCorners(prim, topology, diagnostics);
    return topology;
}

}  // namespace hdhair
