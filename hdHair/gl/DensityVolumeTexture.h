#pragma once
// The hair density volume on the GPU (hdHair/curves/HairDensityGrid.h): σ per
// voxel in a GL_R32F 3-D texture at unit 8, filtered trilinearly between
// voxel centres and clamped at the edges (the grid's margin is empty), as
// shaders/include/densityVolume.glsl reads it. Its mip chain (each level the
// mean σ of the eight voxels under a texel: halvedDensity) serves the cone
// lookups: the mean density over a cone's cross-section. A frame without it
// binds a 1-voxel placeholder of 0.

#include <cstddef>

#include "hdHair/curves/HairDensityGrid.h"
#include "hdHair/gl/GlObjects.h"

namespace hdhair::gl {

class DensityVolumeTexture {
public:
    DensityVolumeTexture();
    // Sends the grid, reallocating only when its size changed; throws
    // std::runtime_error when a side is larger than GL_MAX_3D_TEXTURE_SIZE.
    void update(const DensityGrid& grid);
    // Back to the placeholder, freeing the grid's memory: a frame that
    // shadows no light through the volume holds none of it.
    void release();
    void bind() const;

private:
    Texture texture_;
    glm::ivec3 dims_{0};
    GLsizei levels_ = 1;
};

}  // namespace hdhair::gl
