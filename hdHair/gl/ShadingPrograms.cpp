#include "hdHair/gl/ShadingPrograms.h"

#include <utility>

namespace hdhair::gl {

ShadingPrograms::ShadingPrograms(std::vector<std::string> shaderNames) : shaderNames_(std::move(shaderNames)) {}

const Program& ShadingPrograms::get(ShadingFeatures features) {
    auto found = programs_.find(features.key());
    if (found != programs_.end()) return found->second;
    // Lines go to the rasteriser as the evaluation shader emits them.
    std::vector<std::string> stages;
    for (const std::string& name : shaderNames_)
        if (!(features.strandLines() && name == "strand.geom")) stages.push_back(name);
    Program program = createProgram(stages, {{"include/shadingFeatures.glsl", features.glsl()}});
    return programs_.emplace(features.key(), std::move(program)).first->second;
}

}  // namespace hdhair::gl
