#pragma once
// The frame's hair materials on the GPU: a storage buffer of GpuHairMaterial
// (binding 8), the per-point hair parameters of prims whose parameters vary
// (binding 9), and the materials' tables stacked in one texture array
// (texture unit 1): a tabled Marschner material's azimuthal tables, two
// layers, and a dual-scattering material's fibre layer, as
// shaders/include/hairMaterials.glsl reads them.

#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

#include "hdHair/gl/GlObjects.h"
#include "hdHair/gl/ShadingFeatures.h"
#include "hdHair/gl/UniformBlocks.h"

namespace hdhair::gl {

// `layers` layers of width × height RGBA halves, one after the other.
struct MaterialTableLayers {
    const std::vector<uint16_t>* halfTexels = nullptr;
    int layers = 0;
};

class HairMaterialTable {
public:
    HairMaterialTable();

    // `tables`: stacked in this order from layer 0 (what the materials'
    // modelAndLayer.y and segments.w refer to): Marschner tables
    // (MarschnerTables::halfTexels(), 2 layers) and dual-scattering layers
    // (DualScatteringTable::halfLayer(), 1 layer).
    // `parameterPoints`: two vec4s a record, what materials' modelAndLayer.w index.
    void update(const std::vector<GpuHairMaterial>& materials, const std::vector<glm::vec4>& parameterPoints,
                const std::vector<MaterialTableLayers>& tables, int width, int height);
    void bind() const;

private:
    Buffer materials_;
    size_t materialCapacity_ = 0;
    Buffer parameterPoints_;
    size_t parameterPointCapacity_ = 0;
    Texture tables_;
};

}  // namespace hdhair::gl
