#include "hdHair/plan/FrameRecipe.h"

#include <string>
#include <utility>

#include <fmt/format.h>

#include "hdHair/plan/RenderSettings.h"

namespace hdhair {

namespace {

// The explicit setting that asks for bin-sorted or unsorted transparency by
// name, as "NAME=VALUE", or empty. Only values other than the defaults
// count: a Hydra host echoes a default back as if it were set
// (HdHairRenderDelegate::GetEngineSettings drops those), so an explicit
// transparency=binSorted or sortBins=256 cannot be told from no choice on
// every path, and counts on none.
std::string binSortingAskedFor(const RenderSettings& settings) {
    const SettingValues& values = settings.values();
    if (settings.isExplicitlySet("transparency") && values.transparency == TransparencyPath::Unsorted)
        return "transparency=unsorted";
    if (settings.isExplicitlySet("sortBins") && values.sortBins != RenderSettings().values().sortBins)
        return fmt::format("sortBins={}", values.sortBins);
    return "";
}

}  // namespace

FrameRecipe makeFrameRecipe(const Scene& scene, const RenderSettings& settings, const CameraView& camera,
                            const StrandSummary& strands, const MeshSummary& meshes,
                            const std::vector<DomeEnvironment>& domes, const FrameFallbacks& fallbacks,
                            const std::optional<ShadowMapAssignment>& shadowMaps) {
    const SettingValues& values = settings.values();
    LightPlan lighting = planLights(scene, values, camera, strands, meshes, domes);
    ShadowPlan shadows = planShadows(lighting, values, strands, meshes, shadowMaps);
    TransparencyPlan transparency = planTransparency(values, strands, fallbacks);
    StrandRasterPlan strandRaster =
        planStrandRaster(transparency, values, strands, binSortingAskedFor(settings), fallbacks);
    TessellationPlan tessellation = planTessellation(values, transparency);
    return FrameRecipe{std::move(lighting),     std::move(shadows), std::move(transparency),
                       std::move(strandRaster), tessellation,       planExecution(values)};
}

}  // namespace hdhair
