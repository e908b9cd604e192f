#pragma once
// The programs of one set of shaders, one for each set of shading features
// (ShadingFeatures.h) a draw has asked for: compiled the first time, then
// kept. A frame asks for a few (its light batches and the ids pass), and the
// frames after it for the same ones.

#include <map>
#include <string>
#include <vector>

#include "hdHair/gl/GlObjects.h"
#include "hdHair/gl/ShadingFeatures.h"

namespace hdhair::gl {

class ShadingPrograms {
public:
    explicit ShadingPrograms(std::vector<std::string> shaderNames);

    // The program compiled with `features` (include/shadingFeatures.glsl
    // replaced by features.glsl(); without strand.geom when they ask for
    // strand lines); throws std::runtime_error on driver errors.
    const Program& get(ShadingFeatures features);
    size_t compiled() const { return programs_.size(); }

private:
    std::vector<std::string> shaderNames_;
    std::map<uint64_t, Program> programs_;  // by ShadingFeatures::key()
};

}  // namespace hdhair::gl
