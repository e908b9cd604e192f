#include "hdHair/scene/PrimvarFlattening.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include <fmt/format.h>

#include "hdHair/base/Diagnostics.h"

namespace hdhair {

namespace {

const char* plural(size_t count, const char* singular, const char* many) { return count == 1 ? singular : many; }

}  // namespace

ResolvedPrimvar constantPrimvar(const std::vector<float>& value) {
    return ResolvedPrimvar{Interpolation::Constant, static_cast<int>(value.size()), value};
}

std::string attributeName(const std::string& primvarName) {
    if (primvarName == "widths" || primvarName == "normals") return primvarName;
    return "primvars:" + primvarName;
}

std::string formatPrimvarValue(const std::vector<float>& value) {
    if (value.size() == 1) return fmt::format("{}", value[0]);
    return fmt::format("({})", fmt::join(value, ", "));
}

ResolvedPrimvar primvarFallback(const std::string& problem, const std::vector<float>& fallback,
                                const std::string& where, Diagnostics& diagnostics) {
    diagnostics.warn(where, problem + "; using the fallback " + formatPrimvarValue(fallback));
    return constantPrimvar(fallback);
}

std::string primvarCountProblem(Interpolation authored, size_t expected, const std::string& alternatives,
                                size_t found) {
    return fmt::format("{} interpolation needs {} {}{}, found {}", toString(authored), expected,
                       plural(expected, "value", "values"), alternatives, found);
}

std::optional<FlattenedPrimvar> flattenPrimvar(const Primvar& primvar, const std::vector<float>& fallback,
                                               const std::string& where, Diagnostics& diagnostics) {
    assert(!fallback.empty() && "the fallback is one element and sets the tuple size");
    const int tupleSize = static_cast<int>(fallback.size());
    const size_t tuple = fallback.size();
    if (primvar.tupleSize != tupleSize) {
        primvarFallback(fmt::format("expects {} {} per element, found {} ({})", tupleSize,
                                    plural(tuple, "component", "components"), primvar.tupleSize,
                                    primvar.typeName.empty() ? "untyped" : primvar.typeName),
                        fallback, where, diagnostics);
        return std::nullopt;
    }
    const size_t available = primvar.values.size() / tuple;
    if (primvar.values.size() % tuple != 0) {
        diagnostics.warn(where, fmt::format("{} floats are not whole {}-component elements; ignoring the last {}",
                                            primvar.values.size(), tuple, primvar.values.size() % tuple));
    }

    FlattenedPrimvar flattened;
    flattened.indexed = !primvar.indices.empty();
    if (primvar.indices.empty()) {
        flattened.elements.assign(primvar.values.begin(),
                                  primvar.values.begin() + static_cast<std::ptrdiff_t>(available * tuple));
    } else {
        flattened.elements.resize(primvar.indices.size() * tuple);
        size_t outOfRange = 0;
        size_t firstBad = 0;
        for (size_t i = 0; i < primvar.indices.size(); ++i) {
            const int index = primvar.indices[i];
            const bool valid = index >= 0 && static_cast<size_t>(index) < available;
            const float* source = valid ? primvar.values.data() + static_cast<size_t>(index) * tuple : fallback.data();
            std::copy(source, source + tuple, flattened.elements.begin() + static_cast<std::ptrdiff_t>(i * tuple));
            if (!valid && outOfRange++ == 0) firstBad = i;
        }
        if (outOfRange > 0) {
            diagnostics.warn(where,
                             fmt::format("{} {} out of range for {} {} (first: indices[{}] = {}); using the "
                                         "fallback {} for {}",
                                         outOfRange, plural(outOfRange, "index is", "indices are"), available,
                                         plural(available, "value", "values"), firstBad, primvar.indices[firstBad],
                                         formatPrimvarValue(fallback), plural(outOfRange, "it", "them")));
        }
    }
    flattened.count = flattened.elements.size() / tuple;
    flattened.interpolation = flattened.count == 1 ? Interpolation::Constant : primvar.interpolation;
    return flattened;
}

ResolvedPrimvar resolveConstantPrimvar(FlattenedPrimvar flattened, Interpolation authored,
                                       const std::vector<float>& fallback, const std::string& where,
                                       Diagnostics& diagnostics) {
    if (flattened.count == 0)
        return primvarFallback(primvarCountProblem(authored, 1, "", 0), fallback, where, diagnostics);
    if (flattened.count > 1) {
        diagnostics.warn(where, fmt::format("constant interpolation needs 1 value, found {}; using the first",
                                            flattened.count));
    }
    flattened.elements.resize(fallback.size());
    ResolvedPrimvar resolved{Interpolation::Constant, static_cast<int>(fallback.size()), std::move(flattened.elements)};
    // A constant NaN colour or infinite width would blank or discolour the
    // whole prim: the same repair, and word, as any other element's.
    replaceNonFiniteElements(resolved, fallback, where, diagnostics);
    return resolved;
}

void replaceNonFiniteElements(ResolvedPrimvar& resolved, const std::vector<float>& fallback, const std::string& where,
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
                                        plural(replaced, "element is", "elements are"), first,
                                        formatPrimvarValue(fallback), plural(replaced, "it", "them")));
}

}  // namespace hdhair
