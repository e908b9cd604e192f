#include "hdHair/gl/ShadingPrograms.h"

#include <utility>

namespace hdhair::gl {

ShadingPrograms::ShadingPrograms(std::vector<std::string> shaderNames) : shaderNames_(std::move(shaderNames)) {}

const Program& ShadingPrograms::get(ShadingFeatures features) {
    auto found = programs_.find(features.key());
    if (found != programs_.end()) return found->second;
    Program program = createProgram(shaderNames_, {{"include/shadingFeatures.glsl", features.glsl()}});
    return programs_.emplace(features.key(), std::move(program)).first->second;
}

}  // namespace hdhair::gl
