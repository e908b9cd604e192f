#include "hdHair/plan/TessellationPlanner.h"

#include "hdHair/plan/SettingValues.h"
#include "hdHair/plan/TransparencyPlanner.h"

namespace hdhair {

TessellationPlan planTessellation(const SettingValues& settings, const TransparencyPlan& transparency) {
    TessellationPlan plan;
    plan.mode = settings.tessellation;
    plan.pixelsPerSegment = settings.pixelsPerSegment;
    plan.tolerance = settings.tessellation == Tessellation::ScreenError ? settings.tessellationTolerance : 0.0;
    plan.maxSegmentsPerSpan = settings.maxSegmentsPerSpan;
    // The opaque path draws true widths; every blended path applies coverage.
    plan.minPixelWidth = transparency.path == TransparencyPath::Opaque ? 0.0 : settings.minPixelWidth;
    return plan;
}

}  // namespace hdhair
