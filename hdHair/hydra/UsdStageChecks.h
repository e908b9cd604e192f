#pragma once
// hdhair-record's checks of a stage read through OpenUSD, before and after
// OpenUSD composes it, so that its verdicts are the embedded reader's
// (docs/hard-cases.md, "One catalogue, two readers"):
// - openStageLayers: the root layer and every layer it reaches, opened once
//   (and kept open for UsdStage::Open), refusing a layer that is not a
//   regular file and a stage that would compose more than kMaxComposedPrims
//   prims, bounded from the layers alone before OpenUSD composes anything;
// - compositionProblem: OpenUSD's composition errors (a missing or cyclic
//   reference or sublayer, an unresolved target prim), an error as in the
//   embedded reader;
// - warnAboutCurveTokens: the tokens and element sizes the embedded reader
//   warns about, which UsdImaging repairs without naming the prim;
// - cameraPrimAt: a UsdGeomCamera as the engine's CameraPrim, for the same
//   checkedCamera as the embedded reader's.

#include <functional>
#include <string>
#include <vector>

#include "pxr/usd/sdf/layer.h"
#include "pxr/usd/usd/stage.h"
#include "pxr/usd/usd/timeCode.h"
#include "pxr/usd/usdGeom/camera.h"

#include "hdHair/scene/CameraPrim.h"

namespace hdhair::hydra {

// Why a layer could not be opened, from the errors OpenUSD posted while
// trying: its syntax error as "file:line: what", else its first reason.
std::string layerOpenFailure(const std::string& stagePath, const std::vector<std::string>& errors);

// Opens `stagePath` and every layer its sublayers, references and payloads
// reach; element 0 is the root. Throws InputError for a layer that cannot
// be opened (with OpenUSD's reason, `takeErrors` giving the errors posted),
// is not a regular file, or past the caps.
std::vector<PXR_NS::SdfLayerRefPtr> openStageLayers(const std::string& stagePath,
                                                    const std::function<std::vector<std::string>()>& takeErrors);

// OpenUSD's composition errors as one line naming the first arc, or "".
std::string compositionProblem(const PXR_NS::UsdStageRefPtr& stage);

// Warns (where: the stage, message "<prim>.<attribute>: ...") about curve
// tokens and primvar interpolations hdHair does not know, and element sizes
// that are not positive integers, as the embedded reader words them.
void warnAboutCurveTokens(const PXR_NS::UsdStageRefPtr& stage, const std::string& stagePath,
                          const std::function<void(const std::string& where, const std::string& message)>& warn);

CameraPrim cameraPrimAt(const PXR_NS::UsdGeomCamera& camera, PXR_NS::UsdTimeCode time);

}  // namespace hdhair::hydra
