// prepareCurves (PreparedCurves.h): validate, resolve primvars, change basis
// to Catmull-Rom and move to world space, in parallel over curves.

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <glm/common.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/vec4.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/curves/BasisConversion.h"
#include "hdHair/curves/CurveTopology.h"
#include "hdHair/curves/PreparedCurves.h"
#include "hdHair/curves/PrimvarResolution.h"
#include "hdHair/curves/StrandColorSource.h"
#include "hdHair/scene/SceneValidation.h"

namespace hdhair {

namespace {

// Hair prims hold up to millions of curves: past this many, per-curve warnings
// of one kind are summarised in a single line.
constexpr size_t kMaxCurveWarnings = 10;

enum class CurveStatus : uint8_t {
    Kept,
    KeptUnderLength,  // invalid vertex count, drawn the way HdSt draws it
    TooFewVertices,   // no span to draw
    MissingVertices,  // counts run past the end of points
    NonFinitePoint,
    HugePoint,  // finite, but past kLargestCoordinate
    Invisible,  // hidden through CurvesPrim::invisibleCurves: not drawn, not a defect
};

struct CurveCheck {
    CurveStatus status = CurveStatus::Kept;
    size_t badPoint = 0;  // first non-finite point, relative to the curve
};

bool keeps(CurveStatus status) { return status == CurveStatus::Kept || status == CurveStatus::KeptUnderLength; }

CurveCheck checkCurve(const CurvesPrim& prim, const CurveTopology& topology, size_t curve) {
    CurveCheck check;
    const size_t begin = topology.vertexOffsets[curve];
    const size_t end = topology.vertexOffsets[curve + 1];
    if (end > prim.points.size()) {
        check.status = CurveStatus::MissingVertices;
    } else if (topology.segmentCount(curve) == 0) {
        check.status = CurveStatus::TooFewVertices;
    } else {
        for (size_t p = begin; p < end; ++p) {
            const glm::vec3& point = prim.points[p];
            if (!std::isfinite(point.x) || !std::isfinite(point.y) || !std::isfinite(point.z)) {
                check.status = CurveStatus::NonFinitePoint;
                check.badPoint = p - begin;
                return check;
            }
            if (std::max({std::abs(point.x), std::abs(point.y), std::abs(point.z)}) > kLargestCoordinate) {
                check.status = CurveStatus::HugePoint;
                check.badPoint = p - begin;
                return check;
            }
        }
        if (!isValidVertexCount(topology.kind, topology.vertexCount(curve)))
            check.status = CurveStatus::KeptUnderLength;
    }
    return check;
}

// One warning per affected curve, in curve order, up to kMaxCurveWarnings.
template <typename Describe>
void reportCurves(Diagnostics& diagnostics, const std::string& where, const std::vector<CurveCheck>& checks,
                  CurveStatus status, Describe describe) {
    size_t reported = 0;
    for (size_t i = 0; i < checks.size(); ++i) {
        if (checks[i].status != status) continue;
        if (reported++ < kMaxCurveWarnings) diagnostics.warn(where, describe(i, checks[i]));
    }
    if (reported > kMaxCurveWarnings) {
        diagnostics.warn(where, fmt::format("... and {} more curves like that", reported - kMaxCurveWarnings));
    }
}

void reportCurveChecks(const CurvesPrim& prim, const CurveTopology& topology, const std::vector<CurveCheck>& checks,
                       Diagnostics& diagnostics) {
    const std::string countsWhere = prim.path + ".curveVertexCounts";
    const std::string kind = toString(topology.kind);
    if (topology.vertexTotal() != prim.points.size()) {
        diagnostics.warn(
            prim.path + ".points",
            fmt::format("curveVertexCounts add up to {} vertices, but there are {} points; {}", topology.vertexTotal(),
                        prim.points.size(),
                        topology.vertexTotal() > prim.points.size() ? "dropping the curves whose vertices are missing"
                                                                    : "ignoring the extra points"));
    }
    reportCurves(diagnostics, countsWhere, checks, CurveStatus::KeptUnderLength, [&](size_t i, const CurveCheck&) {
        return fmt::format("curve {} has {} vertices, but {} curves need {}; drawing it as Storm does ({})", i,
                           prim.curveVertexCounts[i], kind, describeVertexCountRule(topology.kind),
                           topology.kind.isPeriodic() ? "wrapping its vertices" : "repeating its last vertex");
    });
    reportCurves(diagnostics, countsWhere, checks, CurveStatus::TooFewVertices, [&](size_t i, const CurveCheck&) {
        return fmt::format("curve {} has {} vertices, too few for a single {} span; skipping it", i,
                           prim.curveVertexCounts[i], kind);
    });
    reportCurves(diagnostics, prim.path + ".points", checks, CurveStatus::MissingVertices,
                 [&](size_t i, const CurveCheck&) {
                     return fmt::format("curve {} needs points [{}, {}), past the last point; dropping the curve", i,
                                        topology.vertexOffsets[i], topology.vertexOffsets[i + 1]);
                 });
    reportCurves(diagnostics, prim.path + ".points", checks, CurveStatus::NonFinitePoint,
                 [&](size_t i, const CurveCheck& check) {
                     return fmt::format("curve {} has a non-finite point (points[{}]); dropping the curve", i,
                                        topology.vertexOffsets[i] + check.badPoint);
                 });
    reportCurves(diagnostics, prim.path + ".points", checks, CurveStatus::HugePoint,
                 [&](size_t i, const CurveCheck& check) {
                     const size_t point = topology.vertexOffsets[i] + check.badPoint;
                     const glm::vec3& p = prim.points[point];
                     return fmt::format("curve {} has a point past {:g} (points[{}] = ({:g}, {:g}, {:g})), where "
                                        "lengths overflow float; dropping the curve",
                                        i, kLargestCoordinate, point, p.x, p.y, p.z);
                 });
}

// Primvars that change how Storm draws curves but that hdHair reads and does
// not honour. Each one is a warning: a groom moved from Storm to hdHair must
// not change its look without saying why. (pointSizeScale is not here: it
// only scales Storm's points drawing of curves, which hdHair does not have;
// its curves ignore it in Storm too.)
void reportPrimvarsNotHonoured(const CurvesPrim& prim, Diagnostics& diagnostics) {
    auto anyNonZero = [](const Primvar& primvar) {
        return std::any_of(primvar.values.begin(), primvar.values.end(), [](float v) { return v != 0.0f; });
    };
    auto where = [&](const char* primvarName) { return prim.path + "." + attributeName(primvarName); };
    if (prim.findPrimvar("normals")) {
        diagnostics.warn(where("normals"),
                         "not used: hdHair draws camera-facing strands, not ribbons oriented by normals");
    }
    if (const Primvar* screenSpace = prim.findPrimvar("screenSpaceWidths"); screenSpace && anyNonZero(*screenSpace)) {
        diagnostics.warn(where("screenSpaceWidths"),
                         "not supported: widths are drawn as object-space diameters, not pixels");
    }
    if (const Primvar* minimum = prim.findPrimvar("minScreenSpaceWidths"); minimum && anyNonZero(*minimum)) {
        diagnostics.warn(where("minScreenSpaceWidths"),
                         "not supported: strands thinner than the minPixelWidth setting (default 1 pixel) are "
                         "drawn that wide, with their coverage as alpha");
    }
}

// Authored negative widths have no meaning (a diameter); clamp them to 0.
void clampNegativeWidths(ResolvedPrimvar& widths, const std::string& primPath, Diagnostics& diagnostics) {
    size_t clamped = 0;
    for (float& width : widths.values) {
        if (width < 0.0f) {
            width = 0.0f;
            ++clamped;
        }
    }
    if (clamped > 0) {
        diagnostics.warn(primPath + ".widths",
                         fmt::format("{} negative {}; clamped to 0", clamped, clamped == 1 ? "width" : "widths"));
    }
}

// The four span controls of one resolved primvar (4 * tupleSize floats):
// vertex data through the span's change of basis, varying data linear between
// the span's two end values, uniform and constant data repeated.
void primvarSpanControls(const ResolvedPrimvar& primvar, const CurveTopology& topology,
                         const SpanStencil& vertexStencil, size_t curve, int span, float* out) {
    const size_t tuple = static_cast<size_t>(primvar.tupleSize);
    auto repeat = [&](const float* value) {
        for (size_t r = 0; r < 4; ++r) std::copy(value, value + tuple, out + r * tuple);
    };
    switch (primvar.interpolation) {
    case Interpolation::Constant: repeat(primvar.element(0)); break;
    case Interpolation::Uniform: repeat(primvar.element(curve)); break;
    case Interpolation::Vertex:
        applyStencil(vertexStencil, primvar.element(topology.vertexOffsets[curve]), primvar.tupleSize, out);
        break;
    case Interpolation::Varying:
    case Interpolation::FaceVarying:
        applyStencil(linearSpanStencil(topology.spanEndCount(curve), topology.kind.isPeriodic(), span),
                     primvar.element(topology.spanEndOffsets[curve]), primvar.tupleSize, out);
        break;
    }
}

// True when every element is the same (a per-curve or per-vertex primvar
// authored with one value everywhere is as good as a constant one).
bool allElementsEqual(const ResolvedPrimvar& primvar) {
    const size_t count = primvar.elementCount(), tuple = static_cast<size_t>(primvar.tupleSize);
    for (size_t e = 1; e < count; ++e)
        if (!std::equal(primvar.element(e), primvar.element(e) + tuple, primvar.element(0))) return false;
    return true;
}

}  // namespace

namespace {

// Values outside a shading primvar's documented range are clamped to it,
// with one warning naming the prim, the primvar, how many and an example.
void clampToDocumentedRange(const CurvesPrim& prim, const ShadingPrimvarRequest& request, ResolvedPrimvar& resolved,
                            Diagnostics& diagnostics) {
    size_t outside = 0;
    float example = 0.0f;
    for (float& value : resolved.values) {
        if (value >= request.minimum && value <= request.maximum) continue;
        if (outside++ == 0) example = value;
        value = std::clamp(value, request.minimum, request.maximum);
    }
    if (outside > 0)
        diagnostics.warn(prim.path + "." + attributeName(request.name),
                         fmt::format("{} value(s) outside the documented range [{}, {}] (e.g. {}); clamped", outside,
                                     request.minimum, request.maximum, example));
}

}  // namespace

// A Catmull-Rom span lies inside the convex hull of its Bezier controls
// B0 = C1, B1 = C1 + (C2-C0)/6, B2 = C2 - (C3-C1)/6, B3 = C2 (its own
// controls do not bound it: CR weights go negative). The same holds for the
// interpolated width, so the largest Bezier width bounds the tube's radius.
void growBoundsBySpan(const StrandControlPoint* c, glm::vec3& lo, glm::vec3& hi) {
    const glm::vec3 positions[4] = {c[1].position, c[1].position + (c[2].position - c[0].position) / 6.0f,
                                    c[2].position - (c[3].position - c[1].position) / 6.0f, c[2].position};
    const float widths[4] = {c[1].width, c[1].width + (c[2].width - c[0].width) / 6.0f,
                             c[2].width - (c[3].width - c[1].width) / 6.0f, c[2].width};
    const float radius = std::max(0.0f, *std::max_element(widths, widths + 4)) * 0.5f;
    for (const glm::vec3& p : positions) {
        lo = glm::min(lo, p - radius);
        hi = glm::max(hi, p + radius);
    }
}

namespace {

// Empty bounds start inverted at the largest float, so any span grows them.
constexpr float kHuge = std::numeric_limits<float>::max();

// Each curve's check, with hidden curves marked Invisible.
std::vector<CurveCheck> checkCurves(const CurvesPrim& prim, const CurveTopology& topology) {
    const size_t curveCount = topology.curveCount();
    std::vector<CurveCheck> checks(curveCount);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, curveCount), [&](const tbb::blocked_range<size_t>& range) {
        for (size_t i = range.begin(); i != range.end(); ++i) checks[i] = checkCurve(prim, topology, i);
    });
    // Hidden curves are not drawn, so their defects are not worth a warning.
    for (int hidden : prim.invisibleCurves)
        if (hidden >= 0 && static_cast<size_t>(hidden) < curveCount)
            checks[static_cast<size_t>(hidden)].status = CurveStatus::Invisible;
    return checks;
}

// The per-strand attributes, resolved against the prim's topology.
struct StrandAttributes {
    ResolvedPrimvar widths, colors, opacities;
    std::vector<ResolvedPrimvar> shading;  // parallel to PreparedCurves::shadingPrimvars
};

// Resolves the requested shading primvars the prim authors; appends their
// prepared form to result.shadingPrimvars and returns the resolved values in the same order.
std::vector<ResolvedPrimvar> resolveShadingPrimvars(const CurvesPrim& prim, const CurveTopology& topology,
                                                    const std::vector<ShadingPrimvarRequest>& shadingPrimvars,
                                                    Diagnostics& diagnostics, PreparedCurves& result) {
    std::vector<ResolvedPrimvar> shading;
    for (const ShadingPrimvarRequest& request : shadingPrimvars) {
        if (!prim.findPrimvar(request.name)) continue;
        ResolvedPrimvar resolved = resolvePrimvar(prim, topology, request.name, request.fallback, diagnostics);
        // A prim of no curves has no elements to carry (found by fuzzCurvePreparation).
        if (resolved.values.empty()) continue;
        clampToDocumentedRange(prim, request, resolved, diagnostics);
        PreparedShadingPrimvar prepared;
        prepared.name = request.name;
        prepared.tupleSize = resolved.tupleSize;
        prepared.varying = !allElementsEqual(resolved);
        if (!prepared.varying) prepared.values.assign(resolved.element(0), resolved.element(0) + resolved.tupleSize);
        result.shadingPrimvars.push_back(std::move(prepared));
        shading.push_back(std::move(resolved));
    }
    return shading;
}

// Widths, colours, opacities and shading primvars, resolved and repaired;
// sets result.colorAuthored and result.shadingPrimvars' constant values.
StrandAttributes resolveStrandAttributes(const CurvesPrim& prim, const CurveTopology& topology,
                                         const std::vector<ShadingPrimvarRequest>& shadingPrimvars,
                                         const StrandColorSource* colors, Diagnostics& diagnostics,
                                         PreparedCurves& result) {
    StrandAttributes attributes;
    attributes.widths = resolvePrimvar(prim, topology, "widths", kFallbackWidth, diagnostics);
    clampNegativeWidths(attributes.widths, prim.path, diagnostics);
    const StrandColorSource ownColors = colors ? StrandColorSource() : strandColorSource(prim, nullptr, diagnostics);
    const StrandColorSource& colorSource = colors ? *colors : ownColors;
    auto resolveChannel = [&](const StrandColorSource::Channel& channel) {
        return channel.constant.empty()
                   ? resolvePrimvar(prim, topology, channel.primvar, channel.fallback, diagnostics)
                   : constantPrimvar(channel.constant);
    };
    attributes.colors = resolveChannel(colorSource.color);
    result.colorAuthored = !colorSource.color.constant.empty() || prim.findPrimvar(colorSource.color.primvar);
    attributes.opacities = resolveChannel(colorSource.opacity);
    attributes.shading = resolveShadingPrimvars(prim, topology, shadingPrimvars, diagnostics, result);
    return attributes;
}

// Per curve, 1 where its spans share controls, else 0 (dropped curves included).
std::vector<uint8_t> curvesSharingControls(const CurveTopology& topology, const std::vector<CurveCheck>& checks,
                                           const StrandAttributes& attributes, const PreparedCurves& result) {
    // Spans share controls when the basis makes them overlap and no
    // attribute is linear per span (varying data's per-span controls
    // (2a-b, a, b, 2b-a) differ between neighbours).
    auto linearPerSpan = [](const ResolvedPrimvar& primvar) {
        return primvar.interpolation == Interpolation::Varying || primvar.interpolation == Interpolation::FaceVarying;
    };
    bool attributesShare = !linearPerSpan(attributes.widths) && !linearPerSpan(attributes.colors) &&
                           !linearPerSpan(attributes.opacities);
    for (size_t k = 0; k < attributes.shading.size(); ++k)
        attributesShare =
            attributesShare && !(result.shadingPrimvars[k].varying && linearPerSpan(attributes.shading[k]));
    const size_t curveCount = topology.curveCount();
    std::vector<uint8_t> shares(curveCount, 0);
    if (attributesShare) {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, curveCount), [&](const tbb::blocked_range<size_t>& range) {
            int lastCount = -1;  // grooms repeat a few vertex counts: test each once
            bool lastShares = false;
            for (size_t i = range.begin(); i != range.end(); ++i) {
                if (!keeps(checks[i].status)) continue;
                const int n = topology.vertexCount(i);
                if (n != lastCount) lastShares = spansShareControls(topology.kind, n);
                lastCount = n;
                shares[i] = lastShares ? 1 : 0;
            }
        });
    }
    return shares;
}

// Where each kept curve's segments and controls go.
struct ControlLayout {
    std::vector<uint8_t> shares;                     // per curve: its spans share controls
    std::vector<size_t> firstSegment, firstControl;  // per curve, plus the totals at the end
    size_t segmentTotal() const { return firstSegment.back(); }
    size_t controlTotal() const { return firstControl.back(); }
};

// The layout of the kept curves' segments and controls; counts them in result.curveCount.
ControlLayout layOutControls(const CurveTopology& topology, const std::vector<CurveCheck>& checks,
                             std::vector<uint8_t> shares, PreparedCurves& result) {
    const size_t curveCount = topology.curveCount();
    ControlLayout layout;
    layout.shares = std::move(shares);
    // Exclusive prefix sums.
    layout.firstSegment.assign(curveCount + 1, 0);
    layout.firstControl.assign(curveCount + 1, 0);
    for (size_t i = 0; i < curveCount; ++i) {
        const bool kept = keeps(checks[i].status);
        const size_t segments = kept ? static_cast<size_t>(topology.segmentCount(i)) : 0;
        layout.firstSegment[i + 1] = layout.firstSegment[i] + segments;
        layout.firstControl[i + 1] =
            layout.firstControl[i] + (segments == 0 ? 0 : layout.shares[i] ? segments + 3 : 4 * segments);
        result.curveCount += kept ? 1 : 0;
    }
    return layout;
}

// Sizes result's control, segment and varying shading arrays for `layout`.
void allocateControls(const ControlLayout& layout, PreparedCurves& result) {
    const size_t controlTotal = layout.controlTotal();
    result.controlPoints.resize(controlTotal);
    result.segmentFirstControl.resize(layout.segmentTotal());
    result.segmentCurve.resize(layout.segmentTotal());
    for (PreparedShadingPrimvar& primvar : result.shadingPrimvars)
        if (primvar.varying) primvar.values.resize(controlTotal * static_cast<size_t>(primvar.tupleSize));
}

// What writing one curve's spans reads.
struct SpanSources {
    const CurvesPrim& prim;
    const CurveTopology& topology;
    const StrandAttributes& attributes;
    const ControlLayout& layout;
    float widthScale;
};

// Writes span `s` of curve `i` (n vertices, `worldPoints` 3n floats) into
// result and grows [lo, hi] by it.
void writeSpan(const SpanSources& sources, size_t i, int n, int s, const float* worldPoints, PreparedCurves& result,
               glm::vec3& lo, glm::vec3& hi) {
    const CurveTopology& topology = sources.topology;
    const StrandAttributes& attributes = sources.attributes;
    const size_t segment = sources.layout.firstSegment[i] + static_cast<size_t>(s);
    // Shared spans step one control; the next span rewrites the
    // three they share with the same values.
    const size_t control = sources.layout.firstControl[i] + static_cast<size_t>(s) * (sources.layout.shares[i] ? 1 : 4);
    result.segmentCurve[segment] = static_cast<uint32_t>(i);
    result.segmentFirstControl[segment] = static_cast<uint32_t>(control);
    StrandControlPoint* controls = &result.controlPoints[control];
    const SpanStencil stencil = catmullRomStencil(topology.kind, n, s);
    float positions[12], widthValues[4], spanColors[12], opacityValues[4];
    applyStencil(stencil, worldPoints, 3, positions);
    primvarSpanControls(attributes.widths, topology, stencil, i, s, widthValues);
    primvarSpanControls(attributes.colors, topology, stencil, i, s, spanColors);
    primvarSpanControls(attributes.opacities, topology, stencil, i, s, opacityValues);
    for (int r = 0; r < 4; ++r) {
        controls[r].position = glm::vec3(positions[3 * r], positions[3 * r + 1], positions[3 * r + 2]);
        controls[r].width = widthValues[r] * sources.widthScale;
        controls[r].color = glm::vec3(spanColors[3 * r], spanColors[3 * r + 1], spanColors[3 * r + 2]);
        controls[r].opacity = opacityValues[r];
    }
    for (size_t k = 0; k < attributes.shading.size(); ++k) {
        PreparedShadingPrimvar& primvar = result.shadingPrimvars[k];
        if (primvar.varying)
            primvarSpanControls(attributes.shading[k], topology, stencil, i, s,
                                &primvar.values[control * static_cast<size_t>(primvar.tupleSize)]);
    }
    growBoundsBySpan(controls, lo, hi);
}

// Writes every kept curve's controls into result (already allocated) and
// sets its bounds.
void writeControls(const SpanSources& sources, const std::vector<CurveCheck>& checks, PreparedCurves& result) {
    const CurveTopology& topology = sources.topology;
    const size_t curveCount = topology.curveCount();
    const glm::dmat4& toWorld = sources.prim.worldTransform;
    std::vector<glm::vec3> curveMin(curveCount, glm::vec3(kHuge));
    std::vector<glm::vec3> curveMax(curveCount, glm::vec3(-kHuge));
    tbb::parallel_for(tbb::blocked_range<size_t>(0, curveCount), [&](const tbb::blocked_range<size_t>& range) {
        std::vector<float> worldPoints;
        for (size_t i = range.begin(); i != range.end(); ++i) {
            if (!keeps(checks[i].status)) continue;
            const int n = topology.vertexCount(i);
            // Affine maps commute with the change of basis (its rows sum to
            // 1), so transforming the vertices first is exact; double
            // precision keeps far-from-origin hair steady.
            worldPoints.resize(3 * static_cast<size_t>(n));
            const glm::vec3* objectPoints = &sources.prim.points[topology.vertexOffsets[i]];
            for (size_t v = 0; v < static_cast<size_t>(n); ++v) {
                const glm::dvec4 p = toWorld * glm::dvec4(glm::dvec3(objectPoints[v]), 1.0);
                for (int c = 0; c < 3; ++c) worldPoints[3 * v + static_cast<size_t>(c)] = static_cast<float>(p[c]);
            }
            for (int s = 0; s < topology.segmentCount(i); ++s)
                writeSpan(sources, i, n, s, worldPoints.data(), result, curveMin[i], curveMax[i]);
        }
    });

    for (size_t i = 0; i < curveCount; ++i) {
        result.boundsMin = glm::min(result.boundsMin, curveMin[i]);
        result.boundsMax = glm::max(result.boundsMax, curveMax[i]);
    }
}

}  // namespace

PreparedCurves prepareCurves(const CurvesPrim& prim, Diagnostics& diagnostics,
                             const std::vector<ShadingPrimvarRequest>& shadingPrimvars,
                             const StrandColorSource* colors) {
    PreparedCurves result;
    result.path = prim.path;
    result.boundsMin = glm::vec3(kHuge);
    result.boundsMax = glm::vec3(-kHuge);
    if (std::string problem = transformProblem(prim.path, prim.worldTransform); !problem.empty()) {
        diagnostics.warn(prim.path, problem);
        return result;
    }

    const CurveTopology topology(prim);
    const std::vector<CurveCheck> checks = checkCurves(prim, topology);
    reportCurveChecks(prim, topology, checks, diagnostics);
    reportPrimvarsNotHonoured(prim, diagnostics);

    const StrandAttributes attributes =
        resolveStrandAttributes(prim, topology, shadingPrimvars, colors, diagnostics, result);
    std::vector<uint8_t> shares = curvesSharingControls(topology, checks, attributes, result);
    const ControlLayout layout = layOutControls(topology, checks, std::move(shares), result);
    const size_t segmentTotal = layout.segmentTotal(), controlTotal = layout.controlTotal();
    if (segmentTotal == 0) return result;
    if (controlTotal > std::numeric_limits<uint32_t>::max()) {
        diagnostics.warn(prim.path, fmt::format("{} curve controls are more than one prim can hold (2^32); not drawn",
                                                controlTotal));
        return result;
    }
    allocateControls(layout, result);

    // Widths are object-space diameters (HdSt scales them by the transform).
    // A non-uniform scale stretches a round tube into an elliptical one, which
    // a width cannot express; the cube root of the volume scale is its mean
    // scale factor, exact for uniform scale.
    const float widthScale =
        static_cast<float>(std::cbrt(std::abs(glm::determinant(glm::dmat3(prim.worldTransform)))));
    writeControls(SpanSources{prim, topology, attributes, layout, widthScale}, checks, result);
    return result;
}

std::string opacityPrimvarName(const CurvesPrim& prim) {
    if (!prim.findPrimvar("displayOpacity") && prim.findPrimvar("opacity")) return "opacity";
    return "displayOpacity";
}

}  // namespace hdhair
