#pragma once
// Which lights shade a frame and in which passes: the stage's lights (at
// most kMaxLights), the domes as lights (domeLighting srbf or sampled,
// DomeLighting.h), the camera light when the stage has none, all in the
// rendering space, cut into batches of lightsPerPass (each batch one more
// draw of everything: the "lightBatch k" passes).

#include <cstddef>
#include <string>
#include <vector>

#include "hdHair/plan/SettingTokens.h"
#include "hdHair/shading/ShadingLight.h"

namespace hdhair {

struct CameraView;
struct DomeEnvironment;
struct FrameRecipe;
struct MeshSummary;
class RenderSettings;
class Scene;
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

// Sets the recipe's lights, domes (and the SRBF lights' shared maps),
// cameraLight, flatShading, meshesLit, lightBatches and lightsOverCap.
// domes: the visible domes as the renderer fitted them (frameDomeEnvironments).
void planLights(FrameRecipe& recipe, const Scene& scene, const RenderSettings& settings, const CameraView& camera,
                const StrandSummary& strands, const MeshSummary& meshes, const std::vector<DomeEnvironment>& domes);

}  // namespace hdhair
