#pragma once
// hdhair-bench --table dome: what the SRBF dome lighting (Ren et al.
// 2010; hdHair/plan/DomeLighting.h) costs and how far it is from its
// reference, per stage, under one latlong texture.
//
// Each stage's own lights are replaced by one DomeLight of the texture
// (casting shadows). Rows, all at the same shadowMapResolution so that the
// shadow scheme, not the map size, is measured:
//  - ambient: the old flat term (domeLighting=ambient), the time base;
//  - SRBF lights 10, 20, 30, 40, 60 (domeLights) with the default 4 maps
//    (domeShadowLights) read with nine taps (domeShadowFilter=taps), against
//    the shadowed reference;
//  - 30 lobes with 0, 1, 8 and 30 maps (30: a map per lobe, the scheme the
//    issue calls too slow), taps, against the shadowed reference;
//  - 30 lobes with 4 and 30 maps read through the convolution optical depth
//    map (domeShadowFilter=mipmap, the default);
//  - SRBF lights 10 to 60 unshadowed, against the unshadowed reference;
//  - the references: domeLighting=sampled, `referenceLights` distant lights,
//    each with its own deep opacity map (or none, unshadowed).
// Errors are relativeColorError (hdHair/image/ImageComparison.h): relative
// RMSE and largest difference over covered pixels. Times are the median of
// `repetitions` frames (after one untimed frame that fits the dome and
// builds the tables), each rebuilding its shadow maps (the dome turned by a
// microradian, BenchLights.h), relative to the ambient frame's median in the
// same run: these machines are shared, and ratios hold better than
// milliseconds. The fit and table build are not in the frame times: they
// are cached (SrbfFit/ and SrbfTables/ benchmarks time them).

#include <string>
#include <vector>

#include "hdHair/plan/CameraView.h"

namespace hdhair {

class Renderer;
class Scene;

struct DomeBenchStage {
    std::string name, path;
    Scene* scene = nullptr;  // its lights are replaced by the dome
    CameraView camera;
};

struct DomeBenchOptions {
    std::string texture;        // the dome's latlong texture
    int repetitions = 3;        // timed frames a row (median)
    int referenceLights = 1024; // domeSampledLights of the reference
    int mapResolution = 256;    // shadowMapResolution of every row
};

// Prints one markdown table a stage (stdout), with progress on stderr.
// Throws what a frame throws (a reference whose maps do not fit).
void printDomeTables(Renderer& renderer, const std::vector<DomeBenchStage>& stages, const DomeBenchOptions& options);

}  // namespace hdhair
