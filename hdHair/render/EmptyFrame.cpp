#include "hdHair/render/EmptyFrame.h"

#include <fmt/format.h>

#include "hdHair/render/RenderResult.h"
#include "hdHair/scene/Scene.h"

namespace hdhair {

std::string whyNothingDrawn(const Scene& scene, const RenderResult& result, size_t warnings) {
    const Image& color = result.color;
    if (color.channels == 4)
        for (size_t i = 3; i < color.pixels.size(); i += 4)
            if (color.pixels[i] > 0.0f) return std::string();
    const size_t curves = scene.curves().size(), meshes = scene.meshes().size();
    if (curves + meshes == 0)
        return warnings == 0 ? std::string()
                             : "nothing drawn: no curves or meshes are left to draw after the warnings above";
    if (result.stats.segments == 0 && result.stats.meshTriangles == 0)
        return fmt::format("nothing drawn: none of the stage's curves and mesh prims ({} and {}) has anything left "
                           "to draw (invisible, or emptied by the repairs in the warnings above)",
                           curves, meshes);
    return fmt::format("nothing drawn: the {} segments and {} triangles lie outside the camera's view or are fully "
                       "transparent (check the camera, its clipping range and opacities)",
                       result.stats.segments, result.stats.meshTriangles);
}

}  // namespace hdhair
