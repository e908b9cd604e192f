#pragma once
// Which lights shade a frame and in which passes: the stage's lights (at
// most kMaxLights), the domes as lights (domeLighting srbf or sampled,
// DomeLighting.h), the camera light when the stage has none, all in the
// rendering space, cut into batches of lightsPerPass (each batch one more
// draw of everything: the "lightBatch k" passes).

#include <cstddef>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "hdHair/image/ColorSpaces.h"
#include "hdHair/plan/DomeLighting.h"
#include "hdHair/plan/SettingTokens.h"
#include "hdHair/shading/ShadingLight.h"

namespace hdhair {

struct CameraView;
struct DomeEnvironment;
struct MeshSummary;
class Scene;
struct SettingValues;
struct StrandSummary;

// The most stage lights a frame shades; more are left out, in path order
// from the last, with a warning. Each light costs every strand drawn once
// more per lightsPerPass lights (hdHair/render/README.md, "Light cap").
constexpr size_t kMaxLights = 1024;

// Whether a frame adds hdHair's camera light (a distant light from the
// eye): the cameraLight setting says on, or auto and the stage has no light
// of its own; never when nothing is lit (flat shading only).
bool usesCameraLight(CameraLightSetting setting, bool stageHasLight, bool anythingLit);

// hdHair's camera light for `camera`: a distant light from the eye.
ShadingLight cameraLightOf(const CameraView& camera, bool castsShadow);

// The lights a frame shades with, and in which passes: the first planner,
// which the shadows' (ShadowPlanner.h) reads.
struct LightPlan {
    ShadingLights lights;  // the stage's lights, plus the camera light when used
    // The space their colours are in, and the frame is shaded in
    // (renderingSpace); the frame converts to Rec.709 from it.
    RenderingSpace renderingSpace = RenderingSpace::LinearRec709;
    bool cameraLight = false;  // the last of `lights` is the camera light
    bool flatShading = false;  // every prim flat: no lights needed
    bool meshesLit = false;    // meshes shaded with the lights (Lambert), else displayColor unlit
    // Light passes: [begin, end) ranges of `lights.lights`, at most
    // lightsPerPass each; always at least one (ambient and unlit shading
    // need a pass too).
    std::vector<std::pair<size_t, size_t>> batches;
    size_t lightsPerPass = 4;
    // The domes as domeLighting=srbf shades them (empty with ambient).
    std::vector<PlannedDome> domes;
    // SRBF lights without a map of their own that read another light's
    // (DomeLighting.h): light index -> the index of the light whose map.
    std::map<size_t, size_t> sharedMaps;
    // Stage lights beyond kMaxLights, left out of the frame.
    size_t overCap = 0;
    // domeLighting=sampled: the domes are sampled distant lights, the
    // reference the SRBF path is measured against, which must not shade a
    // light unshadowed (ShadowPlanner.h).
    bool domesSampled = false;
};

// The lights of a frame, in the rendering space (settings.renderingSpace).
// domes: the visible domes as the renderer fitted them (frameDomeEnvironments).
LightPlan planLights(const Scene& scene, const SettingValues& settings, const CameraView& camera,
                     const StrandSummary& strands, const MeshSummary& meshes,
                     const std::vector<DomeEnvironment>& domes);

}  // namespace hdhair
