#pragma once
// hdHair's TfDebug codes: set TF_DEBUG=HDHAIR_FRAMES in a host's environment
// (usdview, usdrecord) to have the plugin print a line per rendered frame.
// Tests use it to prove that a frame came from the plugin, not only that the
// host exited cleanly.

#include "pxr/base/tf/debug.h"

PXR_NAMESPACE_OPEN_SCOPE

TF_DEBUG_CODES(HDHAIR_FRAMES);

PXR_NAMESPACE_CLOSE_SCOPE
