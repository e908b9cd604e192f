#pragma once
// Supersampling (the `supersampling` setting): a frame rendered with N x N
// samples per pixel, through a camera N times as wide and high, brought back
// to its own size.
//  - Colour: the box filter of BoxDownsample.h over each pixel's samples, in
//    scene-linear pre-multiplied RGBA, so coverage becomes alpha and every
//    sample counts alike.
//  - Depth and ids: those of the pixel's NEAREST sample (least window depth;
//    the first in row order on a tie), never an average: an averaged depth or
//    id names no fragment. This is the rule of the unsupersampled frame
//    (NearestStrandRule.h: a pixel's depth and ids are its nearest fragment
//    at least 0.1 opaque) applied over the pixel's samples, so a strand a
//    host can pick without supersampling stays pickable with it, and depth
//    and ids always name the same fragment. The sample nearest the pixel's
//    centre was the other choice; with an even N there is no such sample,
//    and it would drop strands thinner than the gaps between samples.

#include "hdHair/plan/CameraView.h"

namespace hdhair {

struct RenderResult;

// The camera of a frame with `factor` x `factor` samples per pixel: the same
// view and projection, `factor` times the pixels across and down. Throws
// std::invalid_argument when that is wider or higher than 16384 pixels (GL's
// largest render target on the drivers hdHair runs on).
CameraView supersampledCamera(const CameraView& camera, int factor);

// Resolves a frame rendered through supersampledCamera(camera, factor) in
// place to camera's size (above). The depth image must be there when ids are.
void resolveSupersampling(RenderResult& result, int factor);

}  // namespace hdhair
