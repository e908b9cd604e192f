#include "hdHair/hydra/DebugCodes.h"

#include "pxr/base/tf/registryManager.h"

PXR_NAMESPACE_OPEN_SCOPE

TF_REGISTRY_FUNCTION(TfDebug) {
    TF_DEBUG_ENVIRONMENT_SYMBOL(HDHAIR_FRAMES, "hdHair: one line per frame the render pass renders");
}

PXR_NAMESPACE_CLOSE_SCOPE
