#pragma once
// What the planners know of a frame's prepared scene: measured on the
// prepared curves and meshes before any GL work, so that every decision of
// the frame recipe (FrameRecipe.h) is made from it and the settings alone.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "hdHair/plan/ShadowLightView.h"

namespace hdhair {

// What the frame's strands need, measured on the prepared curves.
struct StrandSummary {
    uint64_t segments = 0;
    // Every control point fully opaque (1 exactly: then every interpolated
    // opacity is 1 too, Catmull-Rom weights summing to one).
    bool allOpaque = true;
    // The thinnest any strand can project, in pixels, at the far side of the
    // strands' bounds (conservative); infinity when there are none.
    double minProjectedWidthPixels = 0.0;
    // The widest any strand can project, at the near side of its bounds
    // (conservative); infinity when the bounds reach the camera, 0 when
    // there are no strands.
    double maxProjectedWidthPixels = 0.0;
    // Per drawn prim, in draw order (FrameInputs::drawn): its widest
    // projected width, as maxProjectedWidthPixels, its segments, and about
    // how many pixels a span covers (its mean span at the middle depth of
    // its bounds; infinity when they reach the camera).
    struct PrimRaster {
        double maxProjectedWidthPixels = 0.0;
        uint64_t segments = 0;
        double fragmentsPerSpan = 0.0;
    };
    std::vector<PrimRaster> prims;
    bool anyLit = true;          // some prim's material is lit (not flat)
    std::string shadingModels;   // the models in use, e.g. "kajiyaKay+marschner"
    size_t perPointPrims = 0;    // prims whose hair parameters vary per curve or vertex
    size_t analyticPrims = 0;    // Marschner prims shaded with per-fragment azimuthal terms
    // Per Marschner material, whether multiple scattering runs and why
    // (HairMaterial::multipleScatteringReason), for the strand pass's reason.
    std::vector<std::string> multipleScattering;
    size_t dualScatteringMaterials = 0;  // those where it runs
    CasterBounds casters;        // what casts shadows: every drawn strand
    // Each drawn prim's span lengths (Bezier control polygons).
    std::vector<const std::vector<float>*> spanLengths;
    // The segments a span would get on average if each were cut into pieces
    // no longer than `length` by its control polygon (at least 1 each).
    double meanSegmentsOfAtMost(double length) const;
};

// What the frame's meshes need, measured on the prepared meshes.
struct MeshSummary {
    size_t meshes = 0;        // visible meshes with at least one triangle
    uint64_t triangles = 0;   // after refinement
    int minRefineLevel = 0, maxRefineLevel = 0;  // the levels drawn
    // The drawn meshes' world bounds: what the light views that shadow the
    // meshes hold besides the hair (ShadowPlanner.h, PlannedShadow::meshView).
    CasterBounds bounds;
    bool changed = false;     // the GPU copy must be sent again
};

}  // namespace hdhair
