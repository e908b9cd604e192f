#pragma once
// Translates a composed .usda stage into the engine's Scene at one time code,
// with the semantics UsdImaging gives the same stage (its prim adapters in
// pxr/usdImaging/usdImaging/):
//
//  - Prims: the prims Stage::traverse() yields (active, defined, not
//    abstract). BasisCurves become CurvesPrim, Mesh MeshPrim, Camera
//    CameraPrim, DistantLight/SphereLight/RectLight/DiskLight/DomeLight
//    LightPrim. Other gprim types hdHair cannot draw (NurbsCurves, Points,
//    Sphere, ...) are reported once per type and skipped.
//  - Transforms: world = parent's world * local, through every ancestor
//    (Xform, Scope, typeless prims alike), restarting from the identity at a
//    prim whose xformOpOrder holds "!resetXformStack!" (XformOps.h).
//  - Visibility: "invisible" on a prim hides it and its whole subtree
//    (UsdGeomImageable::ComputeVisibility); the prims are still added, with
//    visible = false, so a later time can show them again.
//  - Purpose (UsdGeomImageable::ComputePurpose): the purpose authored on the
//    highest ancestor that authors one (or on the prim) applies to the whole
//    subtree; "default" when none does. Geometry (curves, meshes) of purpose
//    "default" and "render" is read; "proxy" and "guide" geometry is skipped
//    unless SceneReadOptions asks for it. This is a final-frame renderer, so
//    it shows what a render shows (UsdGeom: "render" is the purpose for
//    final-quality renders); note that usdrecord's own default is
//    {default, proxy} (its --purposes flag), and usdview shows proxy rather
//    than render, so a stage that hides its render geometry behind proxies
//    will differ from those. Purpose does not apply to cameras or lights
//    (Hydra filters only rprims by render tag).
//  - Attributes are read with Attribute::valueAt(time), so time samples
//    animate; an attribute with no value at that time (declared only, or
//    blocked with None) counts as unauthored.
//  - BasisCurves: type, basis and wrap tokens with USD's fallbacks (cubic,
//    bezier, nonperiodic; an unknown token is reported and the fallback
//    used), curveVertexCounts, points. widths: `primvars:widths` when it has a
//    value, else the `widths` attribute (interpolation from its metadata,
//    vertex when unauthored: UsdGeomCurves::GetWidthsInterpolation); both are
//    stored as primvars["widths"]. normals likewise (`primvars:normals`, else
//    `normals`, vertex by default). Unauthored widths are NOT filled in here:
//    hdHair/curves applies Hydra's fallback.
//  - Every other `primvars:NAME` attribute with a numeric value becomes
//    primvars[NAME] (the "primvars:" prefix stripped, namespaces kept:
//    "primvars:hair:melanin" -> "hair:melanin"), with its
//    `primvars:NAME:indices`, `interpolation` metadata (constant when
//    unauthored, UsdGeomPrimvar::GetInterpolation) and `elementSize`; values
//    become a flat float array with the value's tuple size. Token, string and
//    asset primvars are skipped: they only matter to materials, which are not
//    read yet.
//  - Mesh: points, faceVertexCounts, faceVertexIndices, subdivisionScheme
//    (fallback catmullClark), orientation, interpolateBoundary,
//    faceVaryingLinearInterpolation, triangleSubdivisionRule (tokens kept as
//    authored, checked when the mesh is prepared), holeIndices,
//    cornerIndices and cornerSharpnesses, creaseIndices, creaseLengths and
//    creaseSharpnesses, normals and primvars as for curves.
//  - Camera: projection, focalLength, horizontal/verticalAperture and their
//    offsets, clippingRange, with UsdGeomCamera's fallbacks.
//  - Lights: UsdLux inputs (`inputs:intensity`, `inputs:exposure`,
//    `inputs:color`, `inputs:enableColorTemperature`,
//    `inputs:colorTemperature`, `inputs:normalize`, `inputs:angle`,
//    `inputs:radius`, `inputs:width`, `inputs:height`,
//    `inputs:shaping:cone:angle`, `inputs:shaping:cone:softness`) with the
//    schema fallbacks; files written before USD 21.02 name them without
//    "inputs:" (`intensity`, `shaping:cone:angle`), which is read when the
//    `inputs:` name has no value. DomeLight also `inputs:texture:file` (an
//    asset path, resolved against the directory of the layer that authored
//    the value: resolveAssetPath in Stage.h) and `inputs:texture:format`
//    (token, kept as authored); a texture:file that is not an asset is a
//    warning and leaves the dome untextured instead of skipping the light.
//  - Stage metadata: upAxis, metersPerUnit, start/endTimeCode,
//    timeCodesPerSecond (framesPerSecond when only that is authored, as USD
//    does) into Scene::info().
//
// Bad input. An attribute hdHair needs whose value has the wrong type (points
// authored as float[] rather than point3f[], a token where a number belongs)
// is reported as "file:line:col" + "/Prim.attr: expected ..., found ...; prim
// skipped" and the prim is left out; reading goes on. A transform that cannot
// be evaluated (xformOpOrder naming a missing attribute) throws InputError
// from computeLocalTransform: every prim below it would be misplaced.
//
// readScene adds or replaces the prims it reads and sets Scene::info(); it
// does not remove prims a previous read added (call Scene::clear() first for
// a fresh scene).

#include <memory>
#include <string>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/scene/Scene.h"
#include "hdHair/usda/Stage.h"

namespace hdhair::usda {

struct SceneReadOptions {
    // Geometry purposes read besides "default".
    bool renderPurpose = true;
    bool proxyPurpose = false;
    bool guidePurpose = false;
};

void readScene(const Stage& stage, double time, Scene& scene, Diagnostics& diagnostics,
               const SceneReadOptions& options = {});

// Opens `path` with Stage::open (which throws InputError for a missing or
// malformed file), reads it at `time` into `scene`, and returns the stage so
// that other time codes can be read without parsing the file again.
std::unique_ptr<Stage> readSceneFile(const std::string& path, double time, Scene& scene,
                                     Diagnostics& diagnostics,
                                     const SceneReadOptions& options = {});

}  // namespace hdhair::usda
