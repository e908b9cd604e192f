#pragma once
// How the camera's strands are cut into segments and how thin a strand is
// drawn before its coverage goes into alpha: the tessellation settings and
// the coverage rule (minPixelWidth), which the frame's uniforms carry to the
// strand shaders (gl::FrameUniforms). The light views tessellate by their
// own copy of the same settings (ShadowPlan).

#include "hdHair/plan/SettingTokens.h"

namespace hdhair {

struct SettingValues;
struct TransparencyPlan;

struct TessellationPlan {
    Tessellation mode = Tessellation::ScreenError;
    double pixelsPerSegment = 8.0;  // projectedLength's segment length, pixels
    double tolerance = 0.0;         // screenError's chord error, pixels; 0 with the other modes
    int maxSegmentsPerSpan = 8;
    // Strands thinner than this many pixels are drawn this wide with their
    // alpha scaled down; 0 on the opaque path, which draws true widths.
    double minPixelWidth = 0.0;
};

// The camera's tessellation; the coverage rule only where the strands blend.
TessellationPlan planTessellation(const SettingValues& settings, const TransparencyPlan& transparency);

}  // namespace hdhair
