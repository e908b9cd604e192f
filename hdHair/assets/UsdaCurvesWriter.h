#pragma once
// Writes hair strands (TressFxReader.h's HairStrands) as a .usda stage that
// hdHair and OpenUSD render as it is, printed the way usdcat prints layers
// (examples/usdagen.py): layer metadata, attributes sorted by name, numbers
// with at most 6 significant digits and no exponent.
//
//   #usda 1.0
//   ( doc, defaultPrim = "World", metersPerUnit, upAxis )
//   def Xform "World" (kind = "component")
//       def Camera "main_cam"          (unless UsdaWriteOptions::camera is false)
//       def BasisCurves "<name>"       (one per input)
//       def Mesh "<name>"              (one per mesh input, e.g. a head)
//       def DistantLight "key_light"   (with the camera)
//
// Curves: type cubic, basis catmullRom, wrap pinned. Pinned catmullRom curves
// pass through every authored point, the root and the tip included (the
// UsdGeomBasisCurves spec adds phantom end points), so the strands start at
// the scalp and end at the tips the asset stores, with one width per point and
// nothing to extrapolate. Nonperiodic catmullRom would drop the first and last
// segment of every strand (and TressFX 3.0 strands have only 4 points).
//
// widths (float[], interpolation vertex, written as the `widths` attribute):
//  - with a root or tip width option: a linear root-to-tip taper, scaled per
//    strand by a TressFX 4.0 strand thickness when the file has one;
//  - else the file's per-point widths (.hair thickness), as they are;
//  - else the file's default width (.hair header), one constant value;
//  - else the same taper with automatic widths: root = 0.0015 x the diagonal
//    of the bounding box of every input together (so merged files get equal
//    widths), tip = 0.2 x root. Curves of that width stay visible as thin
//    strands at any framing of the whole asset and never merge into blobs.
// primvars:displayColor: the colour option (constant); else the file's
// per-point colours (vertex); else its default colour (constant); else a
// mid brown (0.4, 0.22, 0.1). primvars:displayOpacity (vertex or constant)
// only when the file has opacities.
// extent: the points' bounds grown by half the largest width.
//
// Meshes: the points as read, in the hair's units and space (no transform),
// faceVertexCounts and faceVertexIndices as authored, subdivisionScheme
// "none" unless asked for (the head is drawn as its polygons), a constant
// displayColor, extent. Normals are not written: hdHair (and Storm) compute
// them from the surface.
//
// Camera (perspective, focalLength 50, apertures 20.955 x 15.2908): looks at
// the centre of the bounds of every point (hair and meshes) from `cameraFrom` (default +Z with
// upAxis Y, -Y with upAxis Z), no roll (the stage's up axis stays up), far
// enough that every point lies inside 85% of the frame; clippingRange from
// half the distance to the nearest point to twice the distance to the
// farthest. Written as xformOp:translate + xformOp:rotateXYZ.
// Light: a DistantLight, intensity 2, angle 1, white, coming from above, in
// front (the camera's side) and a little to the right.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "hdHair/assets/ObjMeshReader.h"
#include "hdHair/assets/TressFxReader.h"

namespace hdhair::convert {

struct CurvesInput {
    std::string name;  // wanted prim name; usdIdentifier() and made unique by the writer
    HairStrands strands;
};

struct MeshInput {
    std::string name;  // wanted prim name, as for curves
    PolygonMesh mesh;
    std::string subdivisionScheme = "none";
    Float3 color{0.72f, 0.56f, 0.48f};  // displayColor
};

struct UsdaWriteOptions {
    std::optional<float> rootWidth, tipWidth;  // either one given: taper (the other automatic)
    std::optional<Float3> color;               // constant displayColor
    char upAxis = 'Y';                         // 'Y' or 'Z': stage metadata; points are not rotated
    double metersPerUnit = 0.01;
    bool camera = true;                        // the camera and the key light
    std::optional<Float3> cameraFrom;          // direction from the bounds' centre to the camera
    std::string doc;                           // layer doc string ("" for none)
};

struct Bounds {
    Float3 min{1e30f, 1e30f, 1e30f}, max{-1e30f, -1e30f, -1e30f};
    bool empty() const { return min.x > max.x; }
    void add(const Float3& p);
    float diagonal() const;  // 0 when empty
};

struct WrittenCurves {
    std::string path;          // "/World/Ratboy_mohawk"
    size_t strands = 0, points = 0;
    std::string widths;        // how widths were chosen: "taper 0.075 -> 0.015", "from the file", ...
};

struct WrittenMesh {
    std::string path;  // "/World/sintel"
    size_t points = 0, faces = 0;
};

struct CurvesUsda {
    std::string text;                  // the whole layer
    std::vector<WrittenCurves> curves;
    std::vector<WrittenMesh> meshes;
    Bounds bounds;                     // of every hair point (automatic widths follow it)
    float rootWidth = 0, tipWidth = 0; // the taper used where one was (automatic or given)
};

// Builds the layer. Throws std::invalid_argument for unusable input (no
// inputs, a strand with fewer than 2 points, attribute arrays whose sizes do
// not match the points, a non-positive width option, an up axis other than
// Y or Z, a zero cameraFrom, a mesh face of fewer than 3 vertices or naming
// a point that does not exist, a subdivision scheme USD does not know).
CurvesUsda buildCurvesUsda(const std::vector<CurvesInput>& inputs, const UsdaWriteOptions& options,
                           const std::vector<MeshInput>& meshes = {});

// Writes text to path through a temporary file beside it and a rename, so a
// reader never sees half a file. Throws std::runtime_error naming the path.
void writeFileAtomically(const std::string& path, const std::string& text);

// A valid USD prim name from any text: characters other than [A-Za-z0-9_]
// become '_', a leading digit gets a '_' prefix, "" becomes "hair".
std::string usdIdentifier(const std::string& text);

// A number as usdcat-style files print it: at most 6 significant digits, no
// exponent, no trailing zeros, "0" for |x| < 1e-6 (and for -0).
std::string formatNumber(double value);

// Every k-th strand so that at most maxStrands remain, spread evenly over the
// file (strand floor(i * n / maxStrands) for i < maxStrands); per-point and
// per-strand arrays follow. maxStrands >= the count returns the input.
HairStrands subsampleStrands(const HairStrands& strands, size_t maxStrands);

// TressFX-style follow strands: `perGuide` copies of each guide strand, each
// offset from it by a fixed random vector in the plane perpendicular to the
// guide at its root, of length up to `radius` (uniform over the disc), carried
// along the strand by parallel transport (so the offset turns with the
// strand), and grown linearly to (1 + tipSeparation) x its root length at the
// tip, as TressFX's tip separation factor spreads follow hairs. Offsets come
// from a fixed-seed hash of the guide and follow index: the same input
// always gives the same strands. Guides stay first in each group: guide 0,
// its follow strands, guide 1, ... Per-point arrays are copied from the guide.
struct FollowOptions {
    int perGuide = 0;
    float radius = 0.0f;
    float tipSeparation = 1.0f;
};
HairStrands addFollowStrands(const HairStrands& strands, const FollowOptions& options);

}  // namespace hdhair::convert
