#pragma once
// Curves in the one form the renderer tessellates: every span of every curve,
// whatever its authored type, basis and wrap, becomes a uniform Catmull-Rom
// segment of four control points (the span runs from the 2nd to the 3rd).
// Consecutive spans of a curve share the three control points they have in
// common where every attribute allows it (spansShareControls, below): a
// Catmull-Rom curve of n vertices stores its n (+2 phantom) vertices once,
// not 4(n-1) controls, which is most of the strands' memory on CPU and GPU.
// Attributes travel with each control point in the same form, so the GPU
// interpolates positions, widths, colours and opacities with the same weights:
//  - vertex primvars go through the same exact change of basis as the points;
//  - varying primvars (linear between span ends) use CR's linear precision:
//    controls (2a-b, a, b, 2b-a) reproduce a + u(b-a) exactly;
//  - uniform and constant primvars repeat one value four times.
// Positions are in world space; widths are world-space diameters.

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace hdhair {

class Diagnostics;
struct CurvesPrim;
struct StrandColorSource;

struct StrandControlPoint {
    glm::vec3 position;  // world space
    float width;         // world-space diameter
    glm::vec3 color;     // linear displayColor
    float opacity;       // displayOpacity (or primvars:opacity, see opacityPrimvarName)
};
static_assert(sizeof(StrandControlPoint) == 32, "tightly packed for the GPU");

// A primvar the renderer asks prepareCurves to carry besides the colours
// (hair parameters: hdHair/plan/HairMaterial.h), with the value an
// authored but unusable primvar falls back to (one element).
struct ShadingPrimvarRequest {
    std::string name;  // e.g. "hdHair:melanin"
    std::vector<float> fallback;
    // The documented range of every component (HdHairAPI's schema): values
    // outside are clamped to it with one warning a prim.
    float minimum = -std::numeric_limits<float>::infinity();
    float maximum = std::numeric_limits<float>::infinity();
};

// A requested primvar as authored on the prim, resolved like the colours.
// Constant when all its values are equal (`values` then holds one element),
// else varying: one element per control point (PreparedCurves::controlPoints,
// shared between spans the same way), following the same interpolation rules
// as displayColor.
struct PreparedShadingPrimvar {
    std::string name;
    int tupleSize = 1;
    bool varying = false;
    std::vector<float> values;

    const float* at(size_t controlPoint) const {
        return values.data() + (varying ? controlPoint : 0) * static_cast<size_t>(tupleSize);
    }
};

struct PreparedCurves {
    std::string path;
    // Every curve's controls, in curve order; segment s's four are
    // controlPoints[segmentFirstControl[s]] onwards (shared with its
    // neighbours where the curve's spans overlap).
    std::vector<StrandControlPoint> controlPoints;
    std::vector<uint32_t> segmentFirstControl;      // per segment
    std::vector<uint32_t> segmentCurve;             // per segment: index of its curve in the prim
    uint32_t curveCount = 0;                        // curves kept (after dropping bad ones)
    glm::vec3 boundsMin{0.0f}, boundsMax{0.0f};     // world space, widths included; min > max when empty
    std::vector<PreparedShadingPrimvar> shadingPrimvars;  // the requested ones that are authored
    // The colours are authored (by the prim's primvar or a bound material),
    // not the fallback grey: Marschner then takes absorption from them.
    bool colorAuthored = false;

    const PreparedShadingPrimvar* findShadingPrimvar(const std::string& name) const {
        for (const PreparedShadingPrimvar& primvar : shadingPrimvars)
            if (primvar.name == name) return &primvar;
        return nullptr;
    }
    const StrandControlPoint* spanControls(size_t segment) const {
        return controlPoints.data() + segmentFirstControl[segment];
    }
    size_t segmentCount() const { return segmentCurve.size(); }
    bool empty() const { return segmentCurve.empty(); }
    // The bytes these arrays hold (for --stats' cpuMemory).
    size_t heldBytes() const {
        size_t bytes = controlPoints.capacity() * sizeof(StrandControlPoint) +
                       (segmentFirstControl.capacity() + segmentCurve.capacity()) * sizeof(uint32_t);
        for (const PreparedShadingPrimvar& primvar : shadingPrimvars) bytes += primvar.values.capacity() * sizeof(float);
        return bytes;
    }
};

// The primvar a strand's opacity comes from: displayOpacity, or, when a
// stage authors only primvars:opacity (as some hair exporters do), that one.
std::string opacityPrimvarName(const CurvesPrim& prim);

// The largest point coordinate a curve may have: past it (1e38, say) the
// squared lengths tessellation and framing take overflow float (past about
// 1.8e19), so such a curve is dropped with a warning, as one with a NaN point.
constexpr float kLargestCoordinate = 1e18f;

// Validates, resolves every primvar (hdHair/curves/PrimvarResolution.h),
// changes basis to Catmull-Rom and transforms to world space, carrying the
// `shadingPrimvars` the prim authors. Colours and opacities come from
// `colors` (hdHair/curves/StrandColorSource.h; nullptr: displayColor and
// displayOpacity). Never throws for bad data: each repair
// is reported to `diagnostics`, naming the prim and the attribute.
// Thread-safe for distinct prims (Hydra syncs prims in parallel).
PreparedCurves prepareCurves(const CurvesPrim& prim, Diagnostics& diagnostics,
                             const std::vector<ShadingPrimvarRequest>& shadingPrimvars = {},
                             const StrandColorSource* colors = nullptr);

// Grows [lo, hi] by the box of the span whose four control points start at
// `controls`, widths included (the bounds PreparedCurves holds are the union
// of these).
void growBoundsBySpan(const StrandControlPoint* controls, glm::vec3& lo, glm::vec3& hi);

}  // namespace hdhair
