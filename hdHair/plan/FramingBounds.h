#pragma once
// The bounds the framing camera (CameraView.h, framingCamera) fits when a
// stage is rendered without --camera: those of every visible point, except
// points far outside the others. One stray point (a rig's NaN repaired to
// 1e38, a vertex at 1e20 left over from a simulation) would otherwise set
// the bounds alone and leave the hair a speck in the middle of an empty frame.
//
// The rule: per axis, the quartiles Q1 and Q3 of every point's coordinate;
// the spread S is the largest Q3 - Q1 of the three axes; a point is an
// outlier when any coordinate lies more than kOutlierSpreads * S below Q1 or
// above Q3. Outliers are left out of the bounds (not out of the frame: they
// are still drawn where the camera sees them), with one warning per prim
// naming it and the first such point. A stage whose points all share one
// spot (S = 0) has none. 1000 spreads keeps legitimate layouts (two grooms
// far apart each hold a quarter of the points, which widens the quartiles)
// and catches what no artist places on purpose.

#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace hdhair {

struct MeshPrim;
struct PreparedCurves;

class Diagnostics;

constexpr double kOutlierSpreads = 1000.0;

struct SceneBounds {
    glm::dvec3 min{1.0}, max{-1.0};  // min > max when the scene has nothing visible
    bool empty() const { return min.x > max.x; }
};

// One prim's world-space points (non-finite ones count as outliers, left
// out of the quartiles and the bounds).
struct FramingPoints {
    std::string path;
    std::vector<glm::dvec3> points;
};

SceneBounds framingBounds(const std::vector<FramingPoints>& prims, Diagnostics& diagnostics);

// A curves prim's points for framing: each span's box, widths included, so
// that with no outliers the bounds are the prepared curves' own.
FramingPoints spanFramingPoints(const PreparedCurves& curves);
// A mesh's authored points in world space (meshes are refined only when
// drawn); none when its transform is not finite.
FramingPoints meshFramingPoints(const MeshPrim& mesh);

}  // namespace hdhair
