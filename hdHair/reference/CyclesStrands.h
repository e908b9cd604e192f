#pragma once
// A prepared curves prim (PreparedCurves.h: uniform Catmull-Rom spans, after
// every repair, basis change and world transform) as the key points of
// Cycles' hair curves.
//
// Cycles draws a hair curve as a Catmull-Rom spline through its keys, with
// the end keys repeated for the end tangents. hdHair's spans are Catmull-Rom
// segments of their own control polygons, which start and end at the 2nd and
// 3rd controls: a curve's first and last controls are phantoms that Cycles
// would pass through. So the keys are not the controls: each span is sampled
// at `pointsPerSpan` equal steps of u (the exact curve hdHair tessellates,
// positions, widths, colours and opacities with the same weights as the
// GPU), and consecutive spans share their end sample. Cycles' spline through
// the samples then differs from hdHair's curve by the interpolation error of
// a cubic sampled that finely: docs/cycles-reference.md has the measured
// deviation. Periodic curves close on their first sample.

#include <cstdint>
#include <string>
#include <vector>

#include "hdHair/curves/PreparedCurves.h"
#include "hdHair/reference/PrincipledHair.h"
#include "hdHair/plan/HairMaterial.h"

namespace hdhair {

struct CyclesStrands {
    std::string path;
    // Flat: emission of the colour (displayColor × opacity, unlit, as
    // hdHair's flat model); otherwise Principled Hair (Kajiya-Kay prims too:
    // it has no physical counterpart, so their colour becomes absorption).
    bool flat = false;
    PrincipledHair hair;
    bool absorptionPerPoint = false;  // `absorption` holds σ_a per key
    std::vector<int32_t> keysPerCurve;
    std::vector<float> positions;   // 3 per key, world space
    std::vector<float> radii;       // 1 per key: half hdHair's width
    std::vector<float> colors;      // 3 per key, the rendering space
    std::vector<float> opacities;   // 1 per key
    std::vector<float> absorption;  // 3 per key when absorptionPerPoint

    size_t keyCount() const { return radii.size(); }
};

CyclesStrands cyclesStrands(const PreparedCurves& prepared, const HairMaterial& material, int pointsPerSpan);

}  // namespace hdhair
