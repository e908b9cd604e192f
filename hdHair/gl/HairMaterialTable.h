#pragma once
// The frame's hair materials on the GPU: a storage buffer of GpuHairMaterial
// (binding 8), the per-point hair parameters of prims whose parameters vary
// (binding 9), and every tabled Marschner material's azimuthal tables stacked
// in one texture array, two layers a material (texture unit 1), as
// shaders/include/hairMaterials.glsl reads them.

#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

#include "hdHair/gl/GlObjects.h"
#include "hdHair/gl/ShadingFeatures.h"
#include "hdHair/gl/UniformBlocks.h"

namespace hdhair::gl {

class HairMaterialTable {
public:
    HairMaterialTable();

    // `tableTexels`: per Marschner material, its tables as half floats, 2
    // layers of width x height RGBA (MarschnerTables::halfTexels()), in the
    // order the materials' modelAndLayer.y refer to (layer 2k for the k-th).
    // `parameterPoints`: two vec4s a record, what materials' modelAndLayer.w index.
    void update(const std::vector<GpuHairMaterial>& materials, const std::vector<glm::vec4>& parameterPoints,
                const std::vector<const std::vector<uint16_t>*>& tableTexels, int width, int height);
    void bind() const;

private:
    Buffer materials_;
    size_t materialCapacity_ = 0;
    Buffer parameterPoints_;
    size_t parameterPointCapacity_ = 0;
    Texture tables_;
};

}  // namespace hdhair::gl
