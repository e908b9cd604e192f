#include "hdHair/meshes/MeshRefinement.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <mutex>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <opensubdiv/far/error.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/meshes/MeshTopology.h"

namespace hdhair {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

struct MeshRefinement::Refiner {
    std::unique_ptr<Far::TopologyRefiner> far;
};

namespace {

// One primvar element for PrimvarRefiner (which needs Clear and
// AddWithWeight): up to four floats, unused ones staying zero.
struct Element {
    float v[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    void Clear() { std::fill(v, v + 4, 0.0f); }
    void AddWithWeight(const Element& source, float weight) {
        for (int i = 0; i < 4; ++i) v[i] += weight * source.v[i];
    }
};

std::vector<Element> toElements(const std::vector<float>& values, int tupleSize) {
    assert(tupleSize >= 1 && tupleSize <= 4);
    std::vector<Element> elements(values.size() / size_t(tupleSize));
    for (size_t e = 0; e < elements.size(); ++e)
        std::copy_n(values.data() + e * size_t(tupleSize), tupleSize, elements[e].v);
    return elements;
}

// OpenSubdiv reports errors and warnings through process-wide callbacks;
// meshes are prepared in parallel, so each thread collects its own, and the
// mesh being refined reports them as its warnings.
thread_local std::vector<std::string>* tCollected = nullptr;

void collectError(Far::ErrorType, const char* message) {
    if (tCollected) tCollected->push_back(message);
}

void collectWarning(const char* message) {
    if (tCollected) tCollected->push_back(message);
}

struct CollectOpenSubdivMessages {
    std::vector<std::string> messages;
    CollectOpenSubdivMessages() {
        static std::once_flag installed;
        std::call_once(installed, [] {
            Far::SetErrorCallback(collectError);
            Far::SetWarningCallback(collectWarning);
        });
        tCollected = &messages;
    }
    ~CollectOpenSubdivMessages() { tCollected = nullptr; }
};

Sdc::SchemeType schemeType(SubdivisionScheme scheme) {
    switch (scheme) {
    case SubdivisionScheme::Loop: return Sdc::SCHEME_LOOP;
    case SubdivisionScheme::Bilinear: return Sdc::SCHEME_BILINEAR;
    case SubdivisionScheme::CatmullClark:
    case SubdivisionScheme::None: break;
    }
    return Sdc::SCHEME_CATMARK;
}

Sdc::Options schemeOptions(const MeshTopology& topology) {
    Sdc::Options options;
    options.SetVtxBoundaryInterpolation(static_cast<Sdc::Options::VtxBoundaryInterpolation>(topology.boundary));
    options.SetFVarLinearInterpolation(static_cast<Sdc::Options::FVarLinearInterpolation>(topology.faceVarying));
    options.SetTriangleSubdivision(static_cast<Sdc::Options::TriangleSubdivision>(topology.triangles));
    options.SetCreasingMethod(Sdc::Options::CREASE_UNIFORM);
    return options;
}

// OpenSubdiv's face-varying channels, pointing into `faceVaryingChannels`.
std::vector<Far::TopologyDescriptor::FVarChannel> fvarChannels(
    [[maybe_unused]] const MeshTopology& topology, const std::vector<std::vector<int>>& faceVaryingChannels) {
    std::vector<Far::TopologyDescriptor::FVarChannel> channels(faceVaryingChannels.size());
    for (size_t c = 0; c < faceVaryingChannels.size(); ++c) {
        const std::vector<int>& values = faceVaryingChannels[c];
        assert(values.size() == topology.faceVertexIndices.size());
        // Every value a channel uses, for OpenSubdiv's value count.
        channels[c].numValues = values.empty() ? 0 : *std::max_element(values.begin(), values.end()) + 1;
        channels[c].valueIndices = values.data();
    }
    return channels;
}

// The indices of the topology's hole faces.
std::vector<int> holeFaces(const MeshTopology& topology) {
    std::vector<int> holes;
    for (size_t f = 0; f < topology.faceCount(); ++f)
        if (topology.hole[f]) holes.push_back(int(f));
    return holes;
}

// The topology as OpenSubdiv takes it; points into `topology`, `channels` and `holes`.
Far::TopologyDescriptor describe(const MeshTopology& topology,
                                 const std::vector<Far::TopologyDescriptor::FVarChannel>& channels,
                                 const std::vector<int>& holes) {
    Far::TopologyDescriptor descriptor;
    descriptor.numVertices = int(topology.points.size());
    descriptor.numFaces = int(topology.faceCount());
    descriptor.numVertsPerFace = topology.faceVertexCounts.data();
    descriptor.vertIndicesPerFace = topology.faceVertexIndices.data();
    descriptor.numCreases = int(topology.creaseSharpnesses.size());
    descriptor.creaseVertexIndexPairs = topology.creaseEdges.data();
    descriptor.creaseWeights = topology.creaseSharpnesses.data();
    descriptor.numCorners = int(topology.corners.size());
    descriptor.cornerVertexIndices = topology.corners.data();
    descriptor.cornerWeights = topology.cornerSharpnesses.data();
    descriptor.numHoles = int(holes.size());
    descriptor.holeIndices = holes.data();
    descriptor.numFVarChannels = int(channels.size());
    descriptor.fvarChannels = channels.data();
    return descriptor;
}

// OpenSubdiv's refiner of the mesh, refined uniformly to `level`; nullptr
// when OpenSubdiv cannot take the mesh. Its messages become warnings.
std::unique_ptr<Far::TopologyRefiner> refineUniformly(const MeshTopology& topology, int level,
                                                      const std::vector<std::vector<int>>& faceVaryingChannels,
                                                      const std::string& primPath, Diagnostics& diagnostics) {
    const std::vector<Far::TopologyDescriptor::FVarChannel> channels = fvarChannels(topology, faceVaryingChannels);
    const std::vector<int> holes = holeFaces(topology);
    const Far::TopologyDescriptor descriptor = describe(topology, channels, holes);

    CollectOpenSubdivMessages messages;
    using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
    std::unique_ptr<Far::TopologyRefiner> far(
        Factory::Create(descriptor, Factory::Options(schemeType(topology.scheme), schemeOptions(topology))));
    if (far) {
        // Limit positions need the last level's full topology.
        Far::TopologyRefiner::UniformOptions uniform(level);
        uniform.fullTopologyInLastLevel = true;
        far->RefineUniform(uniform);
    }
    for (const std::string& message : messages.messages)
        diagnostics.warn(primPath, "OpenSubdiv: " + message);
    if (!far)
        diagnostics.warn(primPath, fmt::format("OpenSubdiv cannot subdivide this mesh ({}); drawn as its cage",
                                               toString(topology.scheme)));
    return far;
}

}  // namespace

MeshRefinement::MeshRefinement(const MeshTopology& topology, int level,
                               const std::vector<std::vector<int>>& faceVaryingChannels, const std::string& primPath,
                               Diagnostics& diagnostics)
    : channels_(faceVaryingChannels) {
    if (level > 0 && topology.scheme != SubdivisionScheme::None && topology.faceCount() > 0) {
        if (std::unique_ptr<Far::TopologyRefiner> far =
                refineUniformly(topology, level, channels_, primPath, diagnostics)) {
            refiner_ = std::make_unique<Refiner>();
            refiner_->far = std::move(far);
        }
    }

    if (!refiner_) {
        keepCage(topology);
        return;
    }
    readRefinedFaces();
    refinePoints(topology);
}

void MeshRefinement::keepCage(const MeshTopology& topology) {
    points_ = topology.points;
    size_t corner = 0;
    for (size_t f = 0; f < topology.faceCount(); ++f) {
        const int n = topology.faceVertexCounts[f];
        if (!topology.hole[f]) {
            faceVertexCounts_.push_back(n);
            baseFaces_.push_back(int(f));
            for (int i = 0; i < n; ++i) {
                faceVertexIndices_.push_back(topology.faceVertexIndices[corner + size_t(i)]);
                cageCorners_.push_back(int(corner) + i);
            }
        }
        corner += size_t(n);
    }
}

void MeshRefinement::readRefinedFaces() {
    const Far::TopologyRefiner& far = *refiner_->far;
    level_ = far.GetMaxLevel();
    const Far::TopologyLevel& last = far.GetLevel(level_);
    for (int f = 0; f < last.GetNumFaces(); ++f) {
        if (last.IsFaceHole(f)) continue;
        Far::ConstIndexArray vertices = last.GetFaceVertices(f);
        faceVertexCounts_.push_back(vertices.size());
        for (int i = 0; i < vertices.size(); ++i) faceVertexIndices_.push_back(vertices[i]);
        int base = f;
        for (int l = level_; l > 0; --l) base = far.GetLevel(l).GetFaceParentFace(base);
        baseFaces_.push_back(base);
    }
}

void MeshRefinement::refinePoints(const MeshTopology& topology) {
    const Far::TopologyRefiner& far = *refiner_->far;
    onLimitSurface_ = topology.scheme == SubdivisionScheme::CatmullClark || topology.scheme == SubdivisionScheme::Loop;
    std::vector<Element> levelData(topology.points.size());
    for (size_t p = 0; p < topology.points.size(); ++p) std::copy_n(&topology.points[p].x, 3, levelData[p].v);
    Far::PrimvarRefiner primvars(far);
    for (int l = 1; l <= level_; ++l) {
        std::vector<Element> next(size_t(far.GetLevel(l).GetNumVertices()));
        primvars.Interpolate(l, levelData, next);
        levelData = std::move(next);
    }
    std::vector<Element> du, dv;
    if (onLimitSurface_) {
        std::vector<Element> limit(levelData.size());
        du.resize(levelData.size());
        dv.resize(levelData.size());
        primvars.Limit(levelData, limit, du, dv);
        levelData = std::move(limit);
    }
    auto vec3 = [](const Element& e) { return glm::vec3(e.v[0], e.v[1], e.v[2]); };
    points_.resize(levelData.size());
    for (size_t v = 0; v < levelData.size(); ++v) points_[v] = vec3(levelData[v]);
    limitNormals_.resize(du.size());
    for (size_t v = 0; v < du.size(); ++v) {
        const glm::vec3 normal = glm::cross(vec3(du[v]), vec3(dv[v]));
        const float length = glm::length(normal);
        limitNormals_[v] = length > 0.0f && std::isfinite(length) ? normal / length : glm::vec3(0.0f);
    }
}

MeshRefinement::~MeshRefinement() = default;

std::vector<float> MeshRefinement::refineVertexData(const std::vector<float>& values, int tupleSize,
                                                    bool linear) const {
    if (!refiner_) return values;
    const Far::TopologyRefiner& far = *refiner_->far;
    Far::PrimvarRefiner primvars(far);
    std::vector<Element> levelData = toElements(values, tupleSize);
    for (int l = 1; l <= level_; ++l) {
        std::vector<Element> next(size_t(far.GetLevel(l).GetNumVertices()));
        if (linear)
            primvars.InterpolateVarying(l, levelData, next);
        else
            primvars.Interpolate(l, levelData, next);
        levelData = std::move(next);
    }
    if (!linear && onLimitSurface_) {
        std::vector<Element> limit(levelData.size());
        primvars.Limit(levelData, limit);
        levelData = std::move(limit);
    }
    std::vector<float> result(levelData.size() * size_t(tupleSize));
    for (size_t e = 0; e < levelData.size(); ++e)
        std::copy_n(levelData[e].v, tupleSize, result.data() + e * size_t(tupleSize));
    return result;
}

std::vector<float> MeshRefinement::refineFaceVaryingData(size_t channel, const std::vector<float>& values,
                                                         int tupleSize) const {
    const size_t tuple = size_t(tupleSize);
    std::vector<float> result;
    result.reserve(faceVertexIndices_.size() * tuple);
    if (!refiner_) {
        for (int corner : cageCorners_) {
            const size_t value = size_t(channels_[channel][size_t(corner)]);
            result.insert(result.end(), values.begin() + std::ptrdiff_t(value * tuple),
                          values.begin() + std::ptrdiff_t((value + 1) * tuple));
        }
        return result;
    }
    const Far::TopologyRefiner& far = *refiner_->far;
    Far::PrimvarRefiner primvars(far);
    const int fvarChannel = int(channel);
    std::vector<Element> levelData = toElements(values, tupleSize);
    // OpenSubdiv counts the channel's values from the largest index used.
    levelData.resize(size_t(far.GetLevel(0).GetNumFVarValues(fvarChannel)));
    for (int l = 1; l <= level_; ++l) {
        std::vector<Element> next(size_t(far.GetLevel(l).GetNumFVarValues(fvarChannel)));
        primvars.InterpolateFaceVarying(l, levelData, next, fvarChannel);
        levelData = std::move(next);
    }
    if (onLimitSurface_) {
        std::vector<Element> limit(levelData.size());
        primvars.LimitFaceVarying(levelData, limit, fvarChannel);
        levelData = std::move(limit);
    }
    const Far::TopologyLevel& last = far.GetLevel(level_);
    for (int f = 0; f < last.GetNumFaces(); ++f) {
        if (last.IsFaceHole(f)) continue;
        Far::ConstIndexArray faceValues = last.GetFaceFVarValues(f, fvarChannel);
        for (int i = 0; i < faceValues.size(); ++i) {
            const Element& element = levelData[size_t(faceValues[i])];
            result.insert(result.end(), element.v, element.v + tuple);
        }
    }
    return result;
}

}  // namespace hdhair
