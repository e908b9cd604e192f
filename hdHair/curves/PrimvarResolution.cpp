#include "hdHair/curves/PrimvarResolution.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include <fmt/format.h>

#include "hdHair/base/Diagnostics.h"

namespace hdhair {

namespace {

std::string formatValue(const std::vector<float>& value) {
    if (value.size() == 1) return fmt::format("{}", value[0]);
    return fmt::format("({})", fmt::join(value, ", "));
}

const char* plural(size_t count, const char* singular, const char* many) { return count == 1 ? singular : many; }

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

// Replaces every element with a NaN or infinite component by the fallback.
void replaceNonFinite(ResolvedPrimvar& resolved, const std::vector<float>& fallback, const std::string& where,
                      Diagnostics& diagnostics) {
    const size_t tuple = static_cast<size_t>(resolved.tupleSize);
    size_t replaced = 0;
    size_t first = 0;
    for (size_t e = 0; e < resolved.elementCount(); ++e) {
        float* element = resolved.values.data() + e * tuple;
        if (std::all_of(element, element + tuple, [](float v) { return std::isfinite(v); })) continue;
        if (replaced++ == 0) first = e;
        std::copy(fallback.begin(), fallback.end(), element);
    }
    if (replaced == 0) return;
    diagnostics.warn(where, fmt::format("{} {} not finite (first: element {}); using the fallback {} for {}", replaced,
                                        plural(replaced, "element is", "elements are"), first, formatValue(fallback),
                                        plural(replaced, "it", "them")));
}

}  // namespace

ResolvedPrimvar constantPrimvar(const std::vector<float>& value) {
    return ResolvedPrimvar{Interpolation::Constant, static_cast<int>(value.size()), value};
}

std::string attributeName(const std::string& primvarName) {
    if (primvarName == "widths" || primvarName == "normals") return primvarName;
    return "primvars:" + primvarName;
}

ResolvedPrimvar resolvePrimvar(const Primvar& primvar, const CurveTopology& topology,
                               const std::vector<float>& fallback, const std::string& primPath,
                               const std::string& primvarName, Diagnostics& diagnostics) {
    assert(!fallback.empty() && "the fallback is one element and sets the tuple size");
    const std::string where = primPath + "." + attributeName(primvarName);
    const int tupleSize = static_cast<int>(fallback.size());
    const size_t tuple = fallback.size();
    auto useFallback = [&](const std::string& problem) {
        diagnostics.warn(where, problem + "; using the fallback " + formatValue(fallback));
        return constantPrimvar(fallback);
    };

    if (primvar.tupleSize != tupleSize) {
        return useFallback(fmt::format("expects {} {} per element, found {} ({})", tupleSize,
                                       plural(tuple, "component", "components"), primvar.tupleSize,
                                       primvar.typeName.empty() ? "untyped" : primvar.typeName));
    }
    const size_t available = primvar.values.size() / tuple;
    if (primvar.values.size() % tuple != 0) {
        diagnostics.warn(where, fmt::format("{} floats are not whole {}-component elements; ignoring the last {}",
                                            primvar.values.size(), tuple, primvar.values.size() % tuple));
    }

    // Flatten through the indices (UsdGeomPrimvar::ComputeFlattened).
    std::vector<float> elements;
    if (primvar.indices.empty()) {
        elements.assign(primvar.values.begin(),
                        primvar.values.begin() + static_cast<std::ptrdiff_t>(available * tuple));
    } else {
        elements.resize(primvar.indices.size() * tuple);
        size_t outOfRange = 0;
        size_t firstBad = 0;
        for (size_t i = 0; i < primvar.indices.size(); ++i) {
            const int index = primvar.indices[i];
            const bool valid = index >= 0 && static_cast<size_t>(index) < available;
            const float* source = valid ? primvar.values.data() + static_cast<size_t>(index) * tuple : fallback.data();
            std::copy(source, source + tuple, elements.begin() + static_cast<std::ptrdiff_t>(i * tuple));
            if (!valid && outOfRange++ == 0) firstBad = i;
        }
        if (outOfRange > 0) {
            diagnostics.warn(where,
                             fmt::format("{} {} out of range for {} {} (first: indices[{}] = {}); using the "
                                         "fallback {} for {}",
                                         outOfRange, plural(outOfRange, "index is", "indices are"), available,
                                         plural(available, "value", "values"), firstBad, primvar.indices[firstBad],
                                         formatValue(fallback), plural(outOfRange, "it", "them")));
        }
    }
    const size_t count = elements.size() / tuple;

    // HdSt treats vertex/varying data of size 1 as constant; UsdImaging does
    // the same for uniform, and one value without metadata can only be constant.
    Interpolation interpolation =
        primvar.interpolation == Interpolation::FaceVarying ? Interpolation::Varying : primvar.interpolation;
    if (count == 1) interpolation = Interpolation::Constant;
    const char* authoredName = toString(primvar.interpolation);
    auto mismatch = [&](size_t expected, const std::string& alternatives) {
        return useFallback(fmt::format("{} interpolation needs {} {}{}, found {}", authoredName, expected,
                                       plural(expected, "value", "values"), alternatives, count));
    };

    ResolvedPrimvar resolved{interpolation, tupleSize, {}};
    switch (interpolation) {
    case Interpolation::Constant:
        if (count == 0) return mismatch(1, "");
        if (count > 1) {
            diagnostics.warn(where,
                             fmt::format("constant interpolation needs 1 value, found {}; using the first", count));
        }
        elements.resize(tuple);
        resolved.values = std::move(elements);
        break;
    case Interpolation::Uniform:
        if (count != topology.curveCount()) return mismatch(topology.curveCount(), "");
        resolved.values = std::move(elements);
        break;
    case Interpolation::Vertex: {
        const size_t expected = topology.vertexTotal();
        // HdSt truncates indexed vertex data that is too long.
        const bool truncatable = !primvar.indices.empty() && count > expected;
        if (count != expected && !truncatable) return mismatch(expected, "");
        elements.resize(expected * tuple);
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
    replaceNonFinite(resolved, fallback, where, diagnostics);
    return resolved;
}

ResolvedPrimvar resolvePrimvar(const CurvesPrim& prim, const CurveTopology& topology, const std::string& primvarName,
                               const std::vector<float>& fallback, Diagnostics& diagnostics) {
    const Primvar* primvar = prim.findPrimvar(primvarName);
    if (!primvar) return constantPrimvar(fallback);
    return resolvePrimvar(*primvar, topology, fallback, prim.path, primvarName, diagnostics);
}

}  // namespace hdhair
