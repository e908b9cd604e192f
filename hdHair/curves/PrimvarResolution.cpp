#include "hdHair/curves/PrimvarResolution.h"

#include <algorithm>
#include <optional>

#include <fmt/format.h>

#include "hdHair/base/Diagnostics.h"

namespace hdhair {

namespace {

// Where varying data's values for each curve start, in each accepted layout.
enum class VaryingLayout {
    Authored,         // varyingCount per curve (USD's implemented size)
    PerVertex,        // n per pinned bspline/catmullRom curve
    PerVertexPlusOne  // n+1 per linear periodic curve (UsdGeom's _ComputeVaryingDataSize)
};

size_t varyingSourceCount(VaryingLayout layout, const CurveTopology& topology, size_t curve) {
    const int n = topology.vertexCount(curve);
    switch (layout) {
    case VaryingLayout::Authored: return topology.varyingOffsets[curve + 1] - topology.varyingOffsets[curve];
    case VaryingLayout::PerVertex: return static_cast<size_t>(n);
    case VaryingLayout::PerVertexPlusOne: return n >= 1 ? static_cast<size_t>(n) + 1 : 0;
    }
    return 0;
}

size_t varyingSourceTotal(VaryingLayout layout, const CurveTopology& topology) {
    size_t total = 0;
    for (size_t i = 0; i < topology.curveCount(); ++i) total += varyingSourceCount(layout, topology, i);
    return total;
}

// Copies one curve's varying values into its span-end slots. Equal counts
// copy; one extra value (linear periodic n+1) is the closing repeat of the
// first and is dropped; two missing values (pinned, nonperiodic-size data)
// belong to the phantom-end spans and repeat the end values; any other
// difference (pinned n = 3 with 2 values) is a linear resampling.
void copyCurveVarying(const float* source, size_t sourceCount, float* target, size_t targetCount, int tupleSize) {
    const size_t tuple = static_cast<size_t>(tupleSize);
    if (targetCount == 0 || sourceCount == 0) return;
    if (sourceCount >= targetCount && sourceCount <= targetCount + 1) {
        std::copy(source, source + targetCount * tuple, target);
        return;
    }
    if (sourceCount + 2 == targetCount) {
        std::copy(source, source + tuple, target);
        std::copy(source, source + sourceCount * tuple, target + tuple);
        std::copy(source + (sourceCount - 1) * tuple, source + sourceCount * tuple, target + (targetCount - 1) * tuple);
        return;
    }
    for (size_t k = 0; k < targetCount; ++k) {
        const double t = targetCount > 1 ? static_cast<double>(k) * static_cast<double>(sourceCount - 1) /
                                               static_cast<double>(targetCount - 1)
                                         : 0.0;
        const size_t i0 = std::min(static_cast<size_t>(t), sourceCount - 1);
        const size_t i1 = std::min(i0 + 1, sourceCount - 1);
        const double f = t - static_cast<double>(i0);
        for (size_t c = 0; c < tuple; ++c) {
            const double a = source[i0 * tuple + c];
            const double b = source[i1 * tuple + c];
            target[k * tuple + c] = static_cast<float>(a + f * (b - a));
        }
    }
}

std::vector<float> expandVarying(const std::vector<float>& elements, VaryingLayout layout,
                                 const CurveTopology& topology, int tupleSize) {
    const size_t tuple = static_cast<size_t>(tupleSize);
    std::vector<float> result(topology.spanEndTotal() * tuple);
    size_t sourceOffset = 0;
    for (size_t i = 0; i < topology.curveCount(); ++i) {
        const size_t sourceCount = varyingSourceCount(layout, topology, i);
        copyCurveVarying(elements.data() + sourceOffset * tuple, sourceCount,
                         result.data() + topology.spanEndOffsets[i] * tuple,
                         static_cast<size_t>(topology.spanEndCount(i)), tupleSize);
        sourceOffset += sourceCount;
    }
    return result;
}

}  // namespace

ResolvedPrimvar resolvePrimvar(const Primvar& primvar, const CurveTopology& topology,
                               const std::vector<float>& fallback, const std::string& primPath,
                               const std::string& primvarName, Diagnostics& diagnostics) {
    const std::string where = primPath + "." + attributeName(primvarName);
    const int tupleSize = static_cast<int>(fallback.size());
    std::optional<FlattenedPrimvar> flattened = flattenPrimvar(primvar, fallback, where, diagnostics);
    if (!flattened) return constantPrimvar(fallback);
    std::vector<float>& elements = flattened->elements;
    const size_t count = flattened->count;

    // Curves have no face-varying rate: it is read as varying, as Storm does.
    Interpolation interpolation = flattened->interpolation == Interpolation::FaceVarying ? Interpolation::Varying
                                                                                         : flattened->interpolation;
    auto mismatch = [&](size_t expected, const std::string& alternatives) {
        return primvarFallback(primvarCountProblem(primvar.interpolation, expected, alternatives, count), fallback,
                               where, diagnostics);
    };

    ResolvedPrimvar resolved{interpolation, tupleSize, {}};
    switch (interpolation) {
    case Interpolation::Constant:
        return resolveConstantPrimvar(std::move(*flattened), primvar.interpolation, fallback, where, diagnostics);
    case Interpolation::Uniform:
        if (count != topology.curveCount()) return mismatch(topology.curveCount(), "");
        resolved.values = std::move(elements);
        break;
    case Interpolation::Vertex: {
        const size_t expected = topology.vertexTotal();
        // HdSt truncates indexed vertex data that is too long.
        const bool truncatable = flattened->indexed && count > expected;
        if (count != expected && !truncatable) return mismatch(expected, "");
        elements.resize(expected * fallback.size());
        resolved.values = std::move(elements);
        break;
    }
    case Interpolation::Varying:
    case Interpolation::FaceVarying: {
        const size_t expected = topology.varyingTotal();
        VaryingLayout layout = VaryingLayout::Authored;
        std::string alternatives;
        if (count != expected) {
            VaryingLayout alternative = VaryingLayout::Authored;
            if (topology.kind.hasPhantomEnds()) alternative = VaryingLayout::PerVertex;
            if (topology.kind.isLinear() && topology.kind.isPeriodic()) alternative = VaryingLayout::PerVertexPlusOne;
            if (alternative != VaryingLayout::Authored) {
                const size_t alternativeTotal = varyingSourceTotal(alternative, topology);
                if (count != alternativeTotal) return mismatch(expected, fmt::format(" (or {})", alternativeTotal));
                layout = alternative;
            } else {
                return mismatch(expected, "");
            }
        }
        resolved.values = expandVarying(elements, layout, topology, tupleSize);
        break;
    }
    }
    replaceNonFiniteElements(resolved, fallback, where, diagnostics);
    return resolved;
}

ResolvedPrimvar resolvePrimvar(const CurvesPrim& prim, const CurveTopology& topology, const std::string& primvarName,
                               const std::vector<float>& fallback, Diagnostics& diagnostics) {
    const Primvar* primvar = prim.findPrimvar(primvarName);
    if (!primvar) return constantPrimvar(fallback);
    return resolvePrimvar(*primvar, topology, fallback, prim.path, primvarName, diagnostics);
}

}  // namespace hdhair
