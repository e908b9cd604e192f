#pragma once
// A checked mesh (MeshTopology) refined on the CPU with OpenSubdiv's Far
// API: uniform refinement to a level (TopologyRefinerFactory<Topology-
// Descriptor>, creases, corners, holes, boundary and face-varying
// interpolation as authored), primvars carried with PrimvarRefiner.
//
// catmullClark and loop at level 1 and above are projected onto their limit
// surface (PrimvarRefiner::Limit), with normals from the limit tangents: a
// head's polygons then lie on the surface a groom was made on (inside it,
// between the vertices, where it is convex), so hair roots are not buried.
// Level 0 and bilinear are the cage itself (Storm draws refine level 0 that
// way too), as is scheme none at any level: those get their normals from
// the faces (MeshPreparation). After one level every catmullClark face is a
// quad and every loop face a triangle, where OpenSubdiv's limit masks are
// exact; at level 0 they would not be for faces of other sizes.

#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace hdhair {

class Diagnostics;
struct MeshTopology;

class MeshRefinement {
public:
    // `faceVaryingChannels`: for each face-varying primvar to refine, the
    // value index of every face corner of `topology` (corners that share a
    // value are smooth across, others are seams). OpenSubdiv's errors are
    // reported to `diagnostics` at `primPath`; a mesh OpenSubdiv cannot take
    // is drawn as its cage, with a warning.
    MeshRefinement(const MeshTopology& topology, int level, const std::vector<std::vector<int>>& faceVaryingChannels,
                   const std::string& primPath, Diagnostics& diagnostics);
    ~MeshRefinement();
    MeshRefinement(const MeshRefinement&) = delete;
    MeshRefinement& operator=(const MeshRefinement&) = delete;

    int level() const { return level_; }                  // 0 for the cage
    bool onLimitSurface() const { return onLimitSurface_; }
    const std::vector<glm::vec3>& points() const { return points_; }
    // Unit normals per refined vertex when onLimitSurface(), else empty;
    // zero where the limit tangents are parallel (a degenerate vertex).
    const std::vector<glm::vec3>& limitNormals() const { return limitNormals_; }
    // The refined faces that are drawn (holes left out), counter-clockwise.
    const std::vector<int>& faceVertexCounts() const { return faceVertexCounts_; }
    const std::vector<int>& faceVertexIndices() const { return faceVertexIndices_; }
    // Per refined face: the face of `topology` it came from.
    const std::vector<int>& baseFaces() const { return baseFaces_; }

    // Data with one element of `tupleSize` (at most 4) per topology point, at
    // each refined vertex: smooth like the points (vertex, limit included)
    // or linear (varying).
    std::vector<float> refineVertexData(const std::vector<float>& values, int tupleSize, bool linear) const;
    // Data of face-varying channel `channel`, one element per value, at each
    // refined face corner (in faceVertexIndices() order).
    std::vector<float> refineFaceVaryingData(size_t channel, const std::vector<float>& values, int tupleSize) const;

private:
    struct Refiner;  // OpenSubdiv's, kept for the primvars

    // Without OpenSubdiv: the cage's points and its faces that are not holes.
    void keepCage(const MeshTopology& topology);
    // The last level's faces that are not holes, and the base face of each.
    void readRefinedFaces();
    // The refined points, and limit normals where the scheme has a limit surface.
    void refinePoints(const MeshTopology& topology);

    std::unique_ptr<Refiner> refiner_;
    std::vector<std::vector<int>> channels_;
    int level_ = 0;
    bool onLimitSurface_ = false;
    std::vector<glm::vec3> points_, limitNormals_;
    std::vector<int> faceVertexCounts_, faceVertexIndices_, baseFaces_;
    std::vector<int> cageCorners_;  // without OpenSubdiv: per drawn corner, the topology's corner
};

}  // namespace hdhair
