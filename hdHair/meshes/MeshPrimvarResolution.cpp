#include "hdHair/meshes/MeshPrimvarResolution.h"

#include <optional>

#include "hdHair/meshes/MeshTopology.h"
#include "hdHair/scene/MeshPrim.h"

namespace hdhair {

namespace {

size_t expectedCount(Interpolation interpolation, const MeshTopology& topology) {
    switch (interpolation) {
    case Interpolation::Constant: return 1;
    case Interpolation::Uniform: return topology.authoredFaceCount;
    case Interpolation::Varying:
    case Interpolation::Vertex: return topology.authoredPointCount;
    case Interpolation::FaceVarying: return topology.authoredCornerCount;
    }
    return 1;
}

}  // namespace

ResolvedPrimvar resolveMeshPrimvar(const Primvar& primvar, const MeshTopology& topology,
                                   const std::vector<float>& fallback, const std::string& primPath,
                                   const std::string& primvarName, Diagnostics& diagnostics) {
    const std::string where = primPath + "." + attributeName(primvarName);
    std::optional<FlattenedPrimvar> flattened = flattenPrimvar(primvar, fallback, where, diagnostics);
    if (!flattened) return constantPrimvar(fallback);
    if (flattened->interpolation == Interpolation::Constant)
        return resolveConstantPrimvar(std::move(*flattened), primvar.interpolation, fallback, where, diagnostics);
    const size_t expected = expectedCount(flattened->interpolation, topology);
    if (flattened->count != expected)
        return primvarFallback(primvarCountProblem(primvar.interpolation, expected, "", flattened->count), fallback,
                               where, diagnostics);
    ResolvedPrimvar resolved{flattened->interpolation, int(fallback.size()), std::move(flattened->elements)};
    replaceNonFiniteElements(resolved, fallback, where, diagnostics);
    return resolved;
}

ResolvedPrimvar resolveMeshPrimvar(const MeshPrim& prim, const MeshTopology& topology, const std::string& primvarName,
                                   const std::vector<float>& fallback, Diagnostics& diagnostics) {
    const Primvar* primvar = prim.findPrimvar(primvarName);
    if (!primvar) return constantPrimvar(fallback);
    return resolveMeshPrimvar(*primvar, topology, fallback, prim.path, primvarName, diagnostics);
}

}  // namespace hdhair
